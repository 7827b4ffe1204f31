#!/usr/bin/env python3
"""include_order_check: no module includes a header of a module above it.

Every module (a folder with its own targets) has a level in ORDER, written once below; a
file may include headers of its own level and of the levels under it. Each
`#include "cover/..."` in a module's sources and headers is mapped to the module whose
include/ folder holds the header (cover/msg/ is generated from idl/cover_msgs.idl), and an
include of a higher level fails the check, naming file, line and header.

  check_include_order.py SOURCE_DIR          check; exit 1 naming each violation
  check_include_order.py SOURCE_DIR --edges  print the module graph as the tree has it
  check_include_order.py --self-test          the check fails on a tree built to break it

A folder named in ORDER that does not exist (yet) is skipped; a folder with an include/
that ORDER does not name fails the check, so that a new module gets a place.
"""

import os
import re
import sys

# Bottom to top. A module is the longest prefix of a file's path named here; modules on
# one line share a level (they may include each other's headers).
ORDER = [
    # The fleet's vocabulary: data types every process shares; Eigen and the standard
    # library only.
    ["vocabulary"],
    # Services without DDS: configuration, logging, clocks, processes, one start-up, shared memory,
    # MAVLink and VRPN codecs, MCAP files, a WebSocket server.
    [
        "services/config",
        "services/logging",
        "services/clock",
        "services/process",
        "services/startup",
        "services/shm",
        "services/mavlink",
        "services/vrpn",
        "services/mcap",
        "services/websocket",
    ],
    # The message catalogue and its converters to the vocabulary.
    ["idl"],
    # DDS: one API over both vendors, and the clock exchange over it.
    ["services/dds", "services/time_sync", "services/sim_clock"],
    # Algorithms, each vehicle's and the ground's: no simulator, no recording, no apps.
    [
        "ugv_agent/imu_filter",
        "ugv_agent/speed_estimator",
        "uav_agent/model",
        "uav_agent/mission/task_file",
    ],
    ["ugv_agent/imu_source", "uav_agent/planner", "uav_agent/sampc"],
    ["uav_agent/mission"],
    ["uav_agent/loop", "uav_agent/wire", "fc_bridge/core", "mocap/core", "task_manager/store"],
    ["task_manager/dispatch"],
    # Recording (recorder, player, bag info, replay, fleet tap): above DDS and the
    # catalogue, below the tools and the live view.
    ["recording"],
    # The simulator, and what runs the loop inside it.
    ["sim/fc", "sim/firmware", "sim/firmware_link", "sim/mocap", "sim"],
    ["sim/closed_loop"],
    # Processes and tools.
    ["foxglove/params", "foxglove/core", "ground_station/params", "ground_station/core"],
    ["tools/cover-launch", "tools/cover", "tools"],
    [
        "uav_agent/app",
        "ugv_agent/app",
        "sim/app",
        "fc_bridge/app",
        "mocap/app",
        "task_manager/app",
        "foxglove/app",
        "ground_station/app",
    ],
    # Tests read everything.
    ["tests"],
]

SOURCE_SUFFIXES = (".hpp", ".h", ".cpp", ".cc", ".ipp")
INCLUDE = re.compile(r'^\s*#\s*include\s*"(cover/[^"]+)"')
SYSTEM_INCLUDE = re.compile(r"^\s*#\s*include\s*<([^>]+)>")
# The vocabulary's own rule: Eigen and the standard library only (standard headers have
# no extension and no folder).
BOTTOM = "vocabulary"


def allowed_at_bottom(header):
    return header.startswith("Eigen/") or ("/" not in header and "." not in header)
SKIP_DIRS = {"build", ".git", "node_modules", "corpus"}


def levels():
    return {prefix: i for i, line in enumerate(ORDER) for prefix in line}


def module_of(path, level_of):
    """Longest prefix of `path` (relative, '/'-separated) named in ORDER."""
    parts = path.split("/")
    for n in range(len(parts) - 1, 0, -1):
        prefix = "/".join(parts[:n])
        if prefix in level_of:
            return prefix
    return None


def walk(root):
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("build"))
        for name in sorted(files):
            yield os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")


def header_owners(root, files, level_of):
    """cover/... include path -> owning module; the unplaced include/ folders."""
    owners, unplaced = {}, set()
    for path in files:
        marker = "/include/cover/"
        if marker not in path or not path.endswith(SOURCE_SUFFIXES):
            continue
        folder, rest = path.split(marker, 1)
        module = module_of(path, level_of)
        if module is None:
            unplaced.add(folder)
            continue
        owners.setdefault("cover/" + rest, set()).add(module)
    return owners, unplaced


def owner_of(header, owners):
    if header.startswith("cover/msg/"):
        return {"idl"}
    return owners.get(header, set())


def self_test():
    """A throw-away tree with one include upwards, one foreign header in the vocabulary and
    one unplaced module: each must be reported, and the fixed tree must pass."""
    import subprocess
    import tempfile

    files = {
        "vocabulary/include/cover/vocabulary/a.hpp": '#include <yaml-cpp/yaml.h>\n#include <vector>\n',
        "uav_agent/mission/include/cover/mission/m.hpp": '#include "cover/vocabulary/a.hpp"\n',
        "idl/wire/src/w.cpp": '#include "cover/vocabulary/a.hpp"\n#include "cover/mission/m.hpp"\n',
        "nowhere/include/cover/nowhere/n.hpp": "\n",
    }
    expected = [
        "idl/wire/src/w.cpp:2: includes cover/mission/m.hpp of uav_agent/mission",
        "vocabulary/include/cover/vocabulary/a.hpp:1: includes <yaml-cpp/yaml.h>",
        "nowhere/include: a module ORDER does not place",
    ]
    with tempfile.TemporaryDirectory() as root:
        for path, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            with open(os.path.join(root, path), "w", encoding="utf-8") as out:
                out.write(text)
        run = subprocess.run([sys.executable, __file__, root], capture_output=True, text=True)
        missing = [line for line in expected if line not in run.stdout]
        if run.returncode != 1 or missing or "violation(s)" not in run.stdout:
            print(f"self-test: exit {run.returncode}, not reported: {missing}\n{run.stdout}")
            return 1
        os.remove(os.path.join(root, "nowhere/include/cover/nowhere/n.hpp"))
        for path in ("idl/wire/src/w.cpp", "vocabulary/include/cover/vocabulary/a.hpp"):
            with open(os.path.join(root, path), "w", encoding="utf-8") as out:
                out.write("#include <vector>\n")
        fixed = subprocess.run([sys.executable, __file__, root], capture_output=True, text=True)
        if fixed.returncode != 0:
            print(f"self-test: the fixed tree fails:\n{fixed.stdout}")
            return 1
    print(f"self-test: {len(expected)} planted violations reported, the fixed tree passes")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) < 2:
        print(__doc__)
        return 2
    root = argv[1]
    edges_only = "--edges" in argv[2:]
    level_of = levels()
    files = list(walk(root))
    owners, unplaced = header_owners(root, files, level_of)
    errors = [f"{folder}/include: a module ORDER does not place" for folder in sorted(unplaced)]
    for header, modules in sorted(owners.items()):
        if len(modules) > 1:
            errors.append(f"{header}: defined by {', '.join(sorted(modules))} (one owner each)")
    edges = {}
    checked = 0
    for path in files:
        if not path.endswith(SOURCE_SUFFIXES):
            continue
        module = module_of(path, level_of)
        if module is None or module == "tests":
            continue
        checked += 1
        with open(os.path.join(root, path), encoding="utf-8", errors="replace") as text:
            for number, line in enumerate(text, 1):
                system = SYSTEM_INCLUDE.match(line)
                if module == BOTTOM and system and not allowed_at_bottom(system.group(1)):
                    errors.append(
                        f"{path}:{number}: includes <{system.group(1)}>; {BOTTOM} uses Eigen "
                        f"and the standard library only"
                    )
                match = INCLUDE.match(line)
                if not match:
                    continue
                header = match.group(1)
                for target in owner_of(header, owners):
                    if target == module:
                        continue
                    edges.setdefault((module, target), []).append(f"{path}:{number}")
                    if level_of[target] > level_of[module]:
                        errors.append(
                            f"{path}:{number}: includes {header} of {target}, a module above "
                            f"{module}"
                        )
    if edges_only:
        for (source, target), where in sorted(edges.items()):
            mark = "  UP" if level_of[target] > level_of[source] else ""
            print(f"{source} -> {target} ({len(where)}, e.g. {where[0]}){mark}")
        return 0
    if checked == 0:
        print(f"include_order_check: no source file found under {root}")
        return 1
    if errors:
        print(f"include_order_check: {len(errors)} violation(s) in {checked} files:")
        for error in errors:
            print("  " + error)
        return 1
    print(f"include_order_check: {checked} files, {len(edges)} module edges, all downwards")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
