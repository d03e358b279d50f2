#pragma once
// Default topic and frame names (DESIGN.md section 2). Nodes use these relative names; launch files
// remap.
namespace adaptive_perception::ros_topics {

constexpr const char* kCameraImage = "camera/image_raw";
constexpr const char* kCameraInfo = "camera/camera_info";
constexpr const char* kCameraLabels = "camera/labels";  // simulator only: true class ids, mono8
constexpr const char* kOdom = "odom";
constexpr const char* kScan = "scan";
constexpr const char* kGroundTruthPose = "ground_truth/pose";  // evaluation only
constexpr const char* kGroundTruthPath = "ground_truth/path";
constexpr const char* kGroundTruthPlace = "ground_truth/place";  // std_msgs/String, simulator only
constexpr const char* kGroundTruthBox = "ground_truth/box";  // PolygonStamped (4 corners), simulator only
constexpr const char* kTrackedObject = "tracked_object";  // TrackedObject
constexpr const char* kPlace = "place";  // PlaceRecognition
constexpr const char* kJointStates = "joint_states";
constexpr const char* kImu = "imu";  // sensor_msgs/Imu: the torso's orientation
constexpr const char* kLightingState = "lighting/state";  // simulator only
constexpr const char* kFieldMap = "field_map";

constexpr const char* kMapFrame = "map";
constexpr const char* kOdomFrame = "odom";
constexpr const char* kBaseFrame = "base_link";
constexpr const char* kHeadPanFrame = "head_pan_link";
constexpr const char* kHeadTiltFrame = "head_tilt_link";
constexpr const char* kCameraFrame = "camera_link";
constexpr const char* kCameraOpticalFrame = "camera_optical_frame";
constexpr const char* kLaserFrame = "laser";

constexpr const char* kHeadPanJoint = "head_pan_joint";
constexpr const char* kHeadTiltJoint = "head_tilt_joint";

}  // namespace adaptive_perception::ros_topics
