// Replays inputs through a fuzz target without libFuzzer (builds with g++, the sanitizer build
// included): `navemu_fuzz_<target> PATH...` runs every file of each PATH (a file or a folder,
// sorted) once. A path that does not exist is reported and skipped (../shared may be absent).
// CTest runs it over tests/fuzz/regressions/<target> (inputs that once failed) and the seeds.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void run_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  int inputs = 0;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path path(argv[i]);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::directory_iterator(path))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const auto& f : files) run_file(f);
      inputs += static_cast<int>(files.size());
    } else if (std::filesystem::is_regular_file(path, ec)) {
      run_file(path);
      ++inputs;
    } else {
      std::printf("%s: absent, skipped\n", argv[i]);
    }
  }
  std::printf("%d inputs replayed without a finding\n", inputs);
  return 0;
}
