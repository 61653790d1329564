// libFuzzer target for the scene loader: any bytes as a scene file must give a Scene
// or an InputError naming the file and key, never a crash, a hang, another exception type or
// a Scene holding a non-finite number. Built and run by scripts/fuzz_scene_loader.sh.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/scene.hpp"

namespace {
// <dir>/scenes/fuzz.yaml beside <dir>/cranes -> the repository's crane files, so `crane: t8036`
// resolves as in a shipped scene.
std::string scenePath() {
  static const std::string path = [] {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("crane_twin_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir / "scenes");
    std::error_code ec;
    std::filesystem::create_directory_symlink(CRANE_TWIN_SOURCE_DIR "/config/cranes",
                                              dir / "cranes", ec);
    return (dir / "scenes" / "fuzz.yaml").string();
  }();
  return path;
}

bool finite(const crane_twin::Scene& s) {
  const double v[] = {s.duration,
                      s.time_step,
                      s.output_interval,
                      s.rho_inf,
                      s.rope.length,
                      s.rope.mode_fraction,
                      s.rope.subdomain_delta,
                      s.rope.damping,
                      s.rope.mass_per_length,
                      s.rope.axial_stiffness,
                      s.rope.bending_stiffness,
                      s.payload_mass,
                      s.trolley_radius,
                      s.slew_angle,
                      s.swing_deg,
                      s.swing_azimuth_deg,
                      s.gravity};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  for (const auto& c : s.commands)
    if (!std::isfinite(c.t) || !std::isfinite(c.slew_rate) || !std::isfinite(c.trolley_speed) ||
        !std::isfinite(c.hoist_speed))
      return false;
  return s.anchor.allFinite() && s.payload_velocity.allFinite();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = scenePath();
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const crane_twin::Scene s = crane_twin::loadScene(path);
    if (!finite(s)) std::abort();  // a non-finite value got through validation
  } catch (const crane_twin::InputError&) {
    // the expected answer to bad input
  }
  return 0;
}
