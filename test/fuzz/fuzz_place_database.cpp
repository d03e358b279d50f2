// libFuzzer target: a place database file (places/place_database.h), opened read-only and read
// whole.
#include <cstdint>

#include "adaptive_perception/places/place_database.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses([&] {
    const auto db = places::PlaceDatabase::open(fuzz::inputFile(data, size, ".sqlite"), true);
    db.places();
    db.edges();
    db.imageCount();
    const places::PlaceIndex index = db.loadIndex();
    db.adjacencyLists(index);
    db.loadFrames();
    // The whole-image descriptors (readDescriptors): as an index and as a reference traversal.
    db.loadDescriptorIndex(index, places::GlobalDescriptorConfig());
    db.loadTraversal(places::GlobalDescriptorConfig());
  });
}
