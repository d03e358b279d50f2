# Unit tests that scripts/run_tests.sh runs from the release (catkin) build and leaves out of the
# sanitizer tree (test/standalone). rbpf_test runs the whole filter over rendered frames: under
# ASan + UBSan its cases took 800 of the 940 CPU-seconds of the sanitized unit tests, against
# about 70 s in release. The code it drives stays under the sanitizers through rbpf_parts_test,
# the image-likelihood and pose-search cases and the fuzz replays.
# Included by CMakeLists.txt and test/standalone/CMakeLists.txt, so the list is written once.
set(AP_RELEASE_ONLY_UNIT_TESTS rbpf_test)
