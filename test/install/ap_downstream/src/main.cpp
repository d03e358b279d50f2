// Uses adaptive_perception from its install space: a message, a service, and a function of the core
// library. Exits 0 and prints one line when all three work.
#include <adaptive_perception/LineSegmentArray.h>
#include <adaptive_perception/SaveMap.h>

#include <cstdio>

#include "adaptive_perception/places/global_descriptor.h"

int main() {
  adaptive_perception::LineSegmentArray lines;
  lines.segments.resize(2);
  adaptive_perception::SaveMap save;
  save.request.path = "map.yaml";
  const std::string cue =
      adaptive_perception::places::descriptorName(adaptive_perception::places::DescriptorKind::kLayout);
  std::printf("ap_downstream: segments=%zu path=%s cue=%s\n", lines.segments.size(),
              save.request.path.c_str(), cue.c_str());
  return lines.segments.size() == 2 && cue == "layout" ? 0 : 1;
}
