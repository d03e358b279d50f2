// libFuzzer target: a camera file (world/robot_camera.h, config/cameras/); an accepted file must
// give a finite camera pose at its joints' limits and at any torso pitch of a standing robot.
#include <cstdint>
#include <cstdlib>

#include "adaptive_perception/world/robot_camera.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  world::RobotCamera c;
  bool accepted = false;
  fuzz::parsesOrRefuses([&] {
    c = world::RobotCamera::loadYaml(fuzz::inputFile(data, size, ".yaml"));
    accepted = true;
  });
  if (accepted)
    for (const double torso : {-0.5, 0.0, 0.5})
      if (!c.baseToOpticalAtTorsoPitch(c.head.min_pan_rad, c.head.max_tilt_rad, torso)
               .matrix()
               .allFinite())
        std::abort();  // an accepted file that places the camera nowhere
  return 0;
}
