// Writes the valid messages of every received type as libFuzzer seed corpora:
// fuzz_seeds DIR  ->  DIR/<type>/seed_<n>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "receive_paths.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seeds DIR\n";
    return 2;
  }
  for (const char* type : {"stereo_frame", "disparity", "stixels", "surface_normals", "extrinsics"}) {
    const std::filesystem::path dir = std::filesystem::path(argv[1]) / type;
    std::filesystem::create_directories(dir);
    const auto seeds = nerv::fuzz::seedMessages(type);
    for (size_t i = 0; i < seeds.size(); ++i) {
      std::ofstream out(dir / ("seed_" + std::to_string(i)), std::ios::binary);
      out.write(reinterpret_cast<const char*>(seeds[i].data()), static_cast<std::streamsize>(seeds[i].size()));
    }
    std::cout << dir.string() << ": " << seeds.size() << " seeds\n";
  }
  return 0;
}
