// Replays a fuzz target's corpus without libFuzzer (the gcc build, ctest): every file in
// the directories or files named on the command line, then every prefix of each at eight
// lengths (truncated input is the commonest hostile input and costs nothing to add).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void run(const std::vector<std::uint8_t>& bytes) {
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  for (int part = 1; part < 8; ++part) {
    const std::vector<std::uint8_t> prefix(bytes.begin(), bytes.begin() + bytes.size() * part / 8);
    LLVMFuzzerTestOneInput(prefix.data(), prefix.size());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: " << argv[0] << " CORPUS_DIR_OR_FILE...\n";
    return 2;
  }
  std::size_t files = 0;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path root(argv[i]);
    if (std::filesystem::is_directory(root)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file()) continue;
        run(read_bytes(entry.path()));
        ++files;
      }
    } else if (std::filesystem::is_regular_file(root)) {
      run(read_bytes(root));
      ++files;
    } else {
      std::cerr << argv[0] << ": no such corpus: " << root << "\n";
      return 2;
    }
  }
  if (files == 0) {
    std::cerr << argv[0] << ": empty corpus\n";
    return 2;
  }
  std::cout << argv[0] << ": " << files << " inputs replayed, contract held\n";
  return 0;
}
