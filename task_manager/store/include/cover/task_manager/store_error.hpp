#pragma once

#include <stdexcept>

namespace cover::task_manager {

// The task store could not do what was asked: SQLite failed (the message carries SQLite's
// text and the file), the file is from a newer schema, an id is unknown, or stored JSON is
// malformed.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cover::task_manager
