// The mutation driver of the text fuzz targets (scene JSON, OBJ) when they are not built for
// libFuzzer: ctest runs it for a few seconds. It replays every seed first (the committed scenes
// or meshes, and every input an earlier fuzz run found: those must never fail again), then
// mutates random seeds with byte edits, splices and tokens that broke loaders before.
//
// usage: TARGET [--seconds S] [--seed N|time] [--ext .json] PATH...   (PATH: a file or a directory;
// --seed time: a new seed each run, printed, so that runs do not replay the same mutants)
// Each input must be accepted or refused with sdfbench::Error (the target catches it); any
// other exception fails the run, a crash or sanitizer report aborts it.
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <sanitizer/common_interface_defs.h>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

// The input being run, written to fuzz_failure<ext> in the working directory when the run dies
// (a sanitizer report, an abort) or one input takes longer than kInputSeconds (a hang), so that
// the failure can be replayed and kept as a regression seed.
constexpr unsigned kInputSeconds = 10;
const std::string* g_current = nullptr;
std::string g_failure_file = "fuzz_failure";
uint64_t g_seed = 1;

void write_current() {
  if (!g_current) return;
  if (std::FILE* f = std::fopen(g_failure_file.c_str(), "wb")) {
    std::fwrite(g_current->data(), 1, g_current->size(), f);
    std::fclose(f);
  }
  std::fprintf(stderr, "fuzz driver (seed %llu): the failing input is in %s\n", static_cast<unsigned long long>(g_seed),
               g_failure_file.c_str());
}

void on_alarm(int) {
  static const char msg[] = "FAIL: one input ran past the fuzz driver's per-input time limit (a hang)\n";
  (void)!write(2, msg, sizeof msg - 1);
  write_current();
  std::_Exit(1);
}

void run_one(const std::string& input) {
  g_current = &input;
  alarm(kInputSeconds);
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
  alarm(0);
  g_current = nullptr;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Tokens that broke (or could break) a loader: numbers out of range, non-numbers, index limits,
// structure characters.
const char* const kTokens[] = {"nan", "inf", "-inf", "abc", "1e400", "-1e400", "1e39", "0", "-1", "-0", "4294967299",
                               "2147483648", "18446744073709551615", "9223372036854775808", "1e-400", "+", "//", "/",
                               " ", "\n", "\r", "\t", "{", "}", "[", "]", "\"", ",", ":", "null", "true", "[0, 0, 0]",
                               "{}", "[]", "v ", "f ", "f 1 2 3\n", "v 0 0 0\n"};

void mutate(std::string& s, const std::vector<std::string>& seeds, std::mt19937_64& rng) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const size_t at = s.empty() ? 0 : rng() % (s.size() + 1);
    const size_t len = s.empty() ? 0 : 1 + rng() % std::min<size_t>(16, s.size() - std::min(at, s.size() - 1));
    switch (rng() % 6) {
      case 0:  // replace a run of characters by a token
        if (at < s.size()) s.replace(at, std::min(len, s.size() - at), kTokens[rng() % std::size(kTokens)]);
        break;
      case 1: s.insert(at, kTokens[rng() % std::size(kTokens)]); break;
      case 2:
        if (at < s.size()) s.erase(at, len);
        break;
      case 3:
        if (at < s.size()) s[at] = static_cast<char>(rng());
        break;
      case 4: {  // splice a piece of another seed
        const std::string& other = seeds[rng() % seeds.size()];
        if (!other.empty()) {
          const size_t from = rng() % other.size();
          s.insert(at, other.substr(from, 1 + rng() % 256));
        }
        break;
      }
      case 5:
        if (at < s.size()) s.insert(at, s.substr(at, len));  // repeat a run (deeper nesting, longer lines)
        break;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 3.0;
  uint64_t seed = 1;
  std::string ext;
  std::vector<std::string> seeds;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seconds" && i + 1 < argc) seconds = std::atof(argv[++i]);
    else if (arg == "--seed" && i + 1 < argc && std::string(argv[i + 1]) == "time" && ++i)
      seed = static_cast<uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());  // printed below
    else if (arg == "--seed" && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--ext" && i + 1 < argc) ext = argv[++i];
    else if (fs::is_directory(arg)) {
      for (const fs::directory_entry& e : fs::directory_iterator(arg))
        if (e.is_regular_file() && (ext.empty() || e.path().extension() == ext)) seeds.push_back(read(e.path()));
    } else {
      seeds.push_back(read(arg));
    }
  }
  g_seed = seed;
  g_failure_file = "fuzz_failure" + ext;
  __sanitizer_set_death_callback(write_current);
  std::signal(SIGALRM, on_alarm);
  if (seeds.empty()) {
    std::fprintf(stderr, "no seeds: the fuzz driver is broken\n");
    return 1;
  }
  std::mt19937_64 rng(seed);
  uint64_t runs = 0;
  try {
    for (const std::string& s : seeds) run_one(s);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      std::string input = seeds[rng() % seeds.size()];
      mutate(input, seeds, rng);
      run_one(input);
      ++runs;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAIL: the loader threw a non-Error exception: %s\n", e.what());
    return 1;
  }
  std::printf("%zu seeds replayed, %llu mutated inputs (seed %llu), no failure\n", seeds.size(),
              static_cast<unsigned long long>(runs), static_cast<unsigned long long>(seed));
  return 0;
}
