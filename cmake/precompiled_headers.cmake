# The headers that most of the core's files parse (the standard library, Eigen, OpenCV), precompiled
# once per target instead of parsed again by every file: both builds compile them in every test run.
# Included by CMakeLists.txt and test/standalone/CMakeLists.txt, so the list is written once.
set(AP_PCH <algorithm> <cmath> <map> <stdexcept> <string> <vector> <Eigen/Core> <Eigen/Geometry>
    <Eigen/Cholesky> <opencv2/core.hpp> <opencv2/imgproc.hpp>)
