// fuzz/standalone_main: runs a fuzz target once over each file named on the command line, without
// libFuzzer. It is how the fuzzers build with gcc (the sanitizer build compiles and links them, so
// they keep up with the readers) and how a crash input is replayed in any build:
// `FUZZER crash-file...`. It generates no inputs; scripts/fuzz does the fuzzing, with clang.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  LLVMFuzzerInitialize(&argc, &argv);
  for (int k = 1; k < argc; ++k) {
    std::ifstream in(argv[k], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "cannot read %s\n", argv[k]);
      return 2;
    }
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%d inputs ran without a defect\n", argc - 1);
  return 0;
}
