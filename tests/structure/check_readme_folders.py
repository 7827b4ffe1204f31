#!/usr/bin/env python3
"""readme_folders_check: README.md's folder table names every top-level folder, and only those.

  check_readme_folders.py SOURCE_DIR

A folder is a top-level directory that is not hidden and not a build tree (build*); the
table is the one under "## What is here", one row per folder, its first cell `name/`.
"""

import os
import re
import sys

ROW = re.compile(r"^\|\s*`([^`/]+)/`\s*\|")


def folders(root):
    return {
        name
        for name in os.listdir(root)
        if os.path.isdir(os.path.join(root, name))
        and not name.startswith(".")
        and not name.startswith("build")
    }


def table(readme):
    listed, inside = [], False
    with open(readme, encoding="utf-8") as text:
        for line in text:
            if line.startswith("## "):
                inside = line.strip() == "## What is here"
                continue
            match = ROW.match(line) if inside else None
            if match:
                listed.append(match.group(1))
    return listed


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    root = argv[1]
    present, listed = folders(root), table(os.path.join(root, "README.md"))
    errors = [f"`{name}/` is not in README.md's folder table" for name in sorted(present - set(listed))]
    errors += [f"README.md lists `{name}/`, which does not exist" for name in sorted(set(listed) - present)]
    errors += [f"README.md lists `{name}/` twice" for name in sorted(set(listed)) if listed.count(name) > 1]
    if not listed:
        errors.append("README.md has no folder table under '## What is here'")
    if errors:
        print("readme_folders_check:\n  " + "\n  ".join(errors))
        return 1
    print(f"readme_folders_check: {len(listed)} folders, each in README.md's table")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
