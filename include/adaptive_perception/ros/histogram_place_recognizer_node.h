#pragma once
// histogram_place_recognizer: topological place recognition (papers/004) with a SQLite place
// database (places/place_database.h) and a Bayes filter over the places' adjacency. By default it
// recognises by the fused whole-image cues (patch-normalised thumbnail and gradient histograms,
// places/global_descriptor.h), which hold across a change of light; ~cue histogram gives the
// paper's colour-histogram correlation.
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/histogram_place_recognizer.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>

#include <map>
#include <memory>
#include <optional>
#include <set>

#include "adaptive_perception/AddPlaceImages.h"
#include "adaptive_perception/PlaceRecognition.h"
#include "adaptive_perception/RemovePlace.h"
#include "adaptive_perception/SetPlaceAdjacency.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/places/place_database.h"
#include "adaptive_perception/places/place_recognizer.h"
#include "adaptive_perception/ros/image_gate.h"
#include "adaptive_perception/ros/node_diagnostics.h"

namespace adaptive_perception {

class HistogramPlaceRecognizerNode {
 public:
  HistogramPlaceRecognizerNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();
  ~HistogramPlaceRecognizerNode();

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onLabel(const std_msgs::StringConstPtr& msg);
  bool onAddImages(AddPlaceImages::Request& req, AddPlaceImages::Response& res);
  bool onRemovePlace(RemovePlace::Request& req, RemovePlace::Response& res);
  bool onSetAdjacency(SetPlaceAdjacency::Request& req, SetPlaceAdjacency::Response& res);
  bool onSave(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  /// Writes the collected images (one transaction per place) and reloads the index.
  std::string flush();
  void reload();
  void publishOverlay(const cv::Mat& bgr, const std_msgs::Header& header,
                      const PlaceRecognition& result);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);

  std::optional<places::PlaceDatabase> db_;
  places::HistogramConfig histograms_;
  places::GlobalDescriptorConfig descriptors_;
  std::unique_ptr<places::PlaceRecognizer> recognizer_;
  bool train_mode_ = false;
  ros_conv::ImageGate gate_{"histogram_place_recognizer", 5.0};
  int train_batch_ = 0, train_every_n_ = 0;  // from ~train_batch, ~train_every_n
  long train_seen_ = 0;
  std::string label_;  // latest ground_truth/place
  // Images being collected, per place.
  std::map<std::string, std::vector<places::TrainingImage>> pending_;
  std::set<std::pair<std::string, std::string>>
      pending_edges_;  // train mode: places walked between
  struct Collect {
    std::string place;
    long remaining = 0;       // images; -1 = no count limit
    double duration_s = 0.0;  // 0 = no time limit
    ros::Time started;        // first collected image
    ros::Time until;
  };
  std::optional<Collect> collect_;

  image_transport::Subscriber image_sub_;
  ros::Subscriber label_sub_;
  ros::Publisher place_pub_;
  image_transport::Publisher overlay_pub_;
  ros::ServiceServer add_srv_, remove_srv_, adjacency_srv_, save_srv_;
  long images_ = 0, bad_images_ = 0, results_ = 0;
  // Evaluation aid: results against the latest ground_truth/place when one is heard.
  long labelled_ = 0, window_right_ = 0, filter_right_ = 0;
  double last_confidence_ = 0.0;
  std::string last_place_;
  ros_conv::NodeDiagnostics diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
