#pragma once

namespace cover::test {

// Registers the listener that makes, points the environment at and removes the scratch
// directories (scratch_dir.hpp). Call once from main, after InitGoogleTest and before any
// thread starts: it sets environment variables.
void install_scratch_listener(const char* argv0);

}  // namespace cover::test
