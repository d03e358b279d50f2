# Precompiled headers: Eigen, OpenCV and the standard library are most of what each core file
# parses (ROS's headers, for the ROS layer). Used by the catkin build (CMakeLists.txt) and the
# sanitizer tree (test/standalone), both built in every test run.
set(AP_PCH <algorithm> <cmath> <map> <stdexcept> <string> <vector> <Eigen/Core> <Eigen/Geometry>
    <Eigen/Cholesky> <opencv2/core.hpp> <opencv2/imgproc.hpp>)
set(AP_ROS_PCH ${AP_PCH} <ros/ros.h> <sensor_msgs/Image.h> <image_transport/image_transport.h>
    <tf2_ros/buffer.h>)
