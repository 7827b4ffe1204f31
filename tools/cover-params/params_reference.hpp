#pragma once

#include <string>
#include <vector>

namespace cover::params_reference {

// One YAML file or section a user edits, with the table of its keys as the parameter
// struct declares them (config::field_table).
struct Section {
  std::string title;   // "SAMPC"
  std::string header;  // the struct's header, from the repository root
  std::string intro;   // which file and section, which process reads it
  std::string table;   // Markdown: key, unit, default, valid, meaning
};

// Every parameter struct a user edits, in the order of docs/parameters.md.
std::vector<Section> sections();

// docs/parameters.md: the whole page, as `cover-params --markdown` prints it.
std::string markdown();

// How `committed` (the file's text) differs from `generated` (markdown()): empty when they
// are equal, otherwise the first differing lines in unified-diff style (-committed,
// +generated) with a few lines of context and the command that regenerates the file.
std::string drift_report(const std::string& committed, const std::string& generated);

}  // namespace cover::params_reference
