#include "adaptive_perception/ros/histogram_place_recognizer_node.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace {
// The node's own parameters' defaults (the recognizer's are in places::PlaceRecognizerConfig).
constexpr char kPlacesDefaultDatabase[] = "places.sqlite", kPlacesDefaultMode[] = "recognise";
constexpr char kDefaultSpaces[] = "all", kDefaultMask[] = "none";
constexpr double kPlacesMaxRate_hz = 5.0;
constexpr int kTrainBatch = 15, kTrainEveryN = 1;
}  // namespace

std::vector<config::ParameterDoc> HistogramPlaceRecognizerNode::parameters() {
  const places::PlaceRecognizerConfig rc;
  return ros_params::joinRows(
      {{{"database", "string", kPlacesDefaultDatabase, "",
         "the SQLite place database (train_places builds one)"},
        {"create_if_missing", "bool", "true", "",
         "start an empty database when the file is missing"},
        {"mode", "string", kPlacesDefaultMode, "recognise, train",
         "train: images labelled by ground_truth/place are stored"},
        {"bins", "int", std::to_string(places::HistogramConfig().bins), "[2, 256]",
         "a new database's histogram bins per band (an existing one must match when set)"},
        {"spaces", "string", kDefaultSpaces, "", "a new database's colour spaces (histogram.h)"},
        {"mask", "string", kDefaultMask, "", "a new database's image mask (MaskConfig::parse)"},
        {"cue", "string", rc.cue, "fused, thumbnail, gradient, chromaticity, layout, histogram",
         "what images are compared by"},
        {"color_space", "string", rc.color_space, "",
         "histogram cue: auto (the paper's most confident space) or a space name"},
        {"method", "string", rc.method, "",
         "histogram cue: auto (the most confident of chi_square, jeffrey, ks) or one distance"}},
       config::describe(places::PlaceRecognizerConfig::fields(), rc),
       {{"max_rate_hz", "double", config::formatReal(kPlacesMaxRate_hz), "[0.01, 1000]",
         "images processed per second of image time at most"},
        {"train_batch", "int", std::to_string(kTrainBatch), "[1, 100000]",
         "train mode: images per place per transaction"},
        {"train_every_n", "int", std::to_string(kTrainEveryN), "[1, 100000]",
         "train mode: keep one labelled image in N"}},
       ros_params::imageIntakeParameters()});
}

HistogramPlaceRecognizerNode::HistogramPlaceRecognizerNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : diagnostics_(nh, "histogram_place_recognizer", 0.1, 100.0) {
  namespace P = ros_params;
  const std::string path = P::getName(pnh, "database", kPlacesDefaultDatabase);
  const bool create = P::get<bool>(pnh, "create_if_missing", true);
  places::HistogramConfig hc;
  hc.bins = P::getInRange(pnh, "bins", hc.bins, 2, 256);
  const bool explicit_settings =
      pnh.hasParam("bins") || pnh.hasParam("spaces") || pnh.hasParam("mask");
  try {
    hc.spaces = places::parseSpaces(P::get<std::string>(pnh, "spaces", kDefaultSpaces));
    hc.mask = places::MaskConfig::parse(P::get<std::string>(pnh, "mask", kDefaultMask));
  } catch (const std::invalid_argument& e) {
    throw P::ParamError(std::string("parameter ~spaces / ~mask: ") + e.what());
  }
  const std::string mode = P::get<std::string>(pnh, "mode", kPlacesDefaultMode);
  if (mode != "recognise" && mode != "recognize" && mode != "train")
    throw P::ParamError("parameter " + pnh.resolveName("mode") + " is '" + mode +
                        "'; allowed: recognise, train");
  train_mode_ = mode == "train";
  places::PlaceRecognizerConfig rc;
  rc.cue = P::get<std::string>(pnh, "cue", rc.cue);
  rc.color_space = P::get<std::string>(pnh, "color_space", rc.color_space);
  rc.method = P::get<std::string>(pnh, "method", rc.method);
  P::loadFields(pnh, places::PlaceRecognizerConfig::fields(), &rc);
  gate_ = ros_conv::ImageGate("histogram_place_recognizer",
                              P::getInRange(pnh, "max_rate_hz", kPlacesMaxRate_hz, 0.01, 1000.0),
                              P::loadImageIntake(pnh));
  train_batch_ = P::getInRange(pnh, "train_batch", kTrainBatch, 1, 100000);
  train_every_n_ = P::getInRange(pnh, "train_every_n", kTrainEveryN, 1, 100000);
  try {
    rc.validate();
    recognizer_ = std::make_unique<places::PlaceRecognizer>(rc);
  } catch (const std::invalid_argument& e) {
    throw P::ParamError(std::string("recognition parameters: ") + e.what());
  }
  const places::DatabaseSettings wanted = places::DatabaseSettings::fromHistogramConfig(hc);
  if (std::filesystem::exists(path)) {
    db_.emplace(places::PlaceDatabase::open(path));
    if (explicit_settings) db_->requireSettings(wanted);
  } else if (create) {
    db_.emplace(places::PlaceDatabase::create(path, wanted));
    ROS_INFO("histogram_place_recognizer: created %s (%s)", path.c_str(),
             wanted.toString().c_str());
  } else {
    throw std::runtime_error(path + ": no such place database (and ~create_if_missing is false)");
  }
  histograms_ = db_->settings().histogramConfig();
  descriptors_ = places::descriptorConfigForMask(histograms_.mask);
  db_->useDescriptors(descriptors_);  // refuses a database whose descriptors have other settings
  reload();

  place_pub_ = nh.advertise<PlaceRecognition>(ros_topics::kPlace, 10);
  overlay_pub_ = image_transport::ImageTransport(pnh).advertise("overlay", 2);
  image_sub_ = image_transport::ImageTransport(nh).subscribe(
      ros_topics::kCameraImage, 2, &HistogramPlaceRecognizerNode::onImage, this,
      ros_params::imageTransportHints(pnh));
  label_sub_ =
      nh.subscribe(ros_topics::kGroundTruthPlace, 10, &HistogramPlaceRecognizerNode::onLabel, this);
  add_srv_ = pnh.advertiseService("add_images", &HistogramPlaceRecognizerNode::onAddImages, this);
  remove_srv_ =
      pnh.advertiseService("remove_place", &HistogramPlaceRecognizerNode::onRemovePlace, this);
  adjacency_srv_ =
      pnh.advertiseService("set_adjacency", &HistogramPlaceRecognizerNode::onSetAdjacency, this);
  save_srv_ = pnh.advertiseService("save", &HistogramPlaceRecognizerNode::onSave, this);
  diagnostics_.add("place database", this, &HistogramPlaceRecognizerNode::diagnose);
  ROS_INFO("histogram_place_recognizer: %s mode, database %s: %zu places, %ld images",
           train_mode_ ? "train" : "recognise", path.c_str(), db_->places().size(),
           db_->imageCount());
}

HistogramPlaceRecognizerNode::~HistogramPlaceRecognizerNode() {
  // One summary line (the demo prints it); accuracy only when ground_truth/place was heard.
  std::printf(
      "histogram_place_recognizer: images=%ld dropped=%ld results=%ld labelled=%ld "
      "window_accuracy=%.3f filter_accuracy=%.3f\n",
      images_, bad_images_ + gate_.badImages(), results_, labelled_,
      labelled_ > 0 ? static_cast<double>(window_right_) / labelled_ : -1.0,
      labelled_ > 0 ? static_cast<double>(filter_right_) / labelled_ : -1.0);
  std::fflush(stdout);
  try {
    if (!pending_.empty()) ROS_INFO("histogram_place_recognizer: %s", flush().c_str());
  } catch (const std::exception& e) {
    ROS_ERROR("histogram_place_recognizer: images collected but not stored: %s", e.what());
  }
}

void HistogramPlaceRecognizerNode::reload() {
  places::PlaceIndex index = db_->loadIndex();
  std::vector<std::vector<int>> adj = db_->adjacencyLists(index);
  places::PlaceDescriptorIndex descriptors = db_->loadDescriptorIndex(index, descriptors_);
  try {
    recognizer_->setDatabase(std::move(index), std::move(adj), std::move(descriptors));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(db_->path() + ": " + e.what() + " (parameter ~cue)");
  }
}

std::string HistogramPlaceRecognizerNode::flush() {
  std::string msg;
  for (auto& [place, images] : pending_) {
    if (images.empty()) continue;
    const int n = db_->addImages(place, images);
    msg += (msg.empty() ? "" : ", ") + std::to_string(n) + " images to '" + place + "'";
  }
  pending_.clear();
  // Edges walked in train mode, once both places are stored.
  const auto stored = db_->places();
  auto known = [&](const std::string& n) {
    return std::any_of(stored.begin(), stored.end(),
                       [&](const places::PlaceInfo& p) { return p.name == n; });
  };
  for (auto it = pending_edges_.begin(); it != pending_edges_.end();) {
    if (known(it->first) && known(it->second)) {
      db_->setAdjacent(it->first, it->second);
      it = pending_edges_.erase(it);
    } else {
      ++it;
    }
  }
  reload();
  return msg.empty() ? "nothing to store" : "stored " + msg;
}

void HistogramPlaceRecognizerNode::onLabel(const std_msgs::StringConstPtr& msg) {
  if (train_mode_ && !label_.empty() && msg->data != label_ && msg->data != "none" &&
      label_ != "none") {
    // The robot walked from one place into the next: they are adjacent (stored with the images).
    pending_edges_.insert(std::minmax(label_, msg->data));
  }
  label_ = msg->data;
}

void HistogramPlaceRecognizerNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  cv::Mat bgr;
  bool restart = false;
  const auto verdict = gate_.accept(*msg, &bgr, &restart);
  if (restart) recognizer_->reset();
  if (verdict != ros_conv::ImageGate::Result::kProcess) return;
  places::ImageHistograms h;
  places::ImageDescriptors d;
  try {
    h = places::computeHistograms(bgr, histograms_);
    d = places::computeDescriptors(bgr, descriptors_);
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "histogram_place_recognizer: image dropped: %s", e.what());
    ++bad_images_;
    return;
  }
  ++images_;
  diagnostics_.tick();

  // Collecting training images: from a service request, or in train mode from the labels.
  std::string target;
  if (collect_) {
    target = collect_->place;
  } else if (train_mode_ && !label_.empty() && label_ != "none" &&
             train_seen_++ % train_every_n_ == 0) {
    target = label_;
  }
  if (!target.empty()) {
    char src[64];
    std::snprintf(src, sizeof(src), "%s@%.3f", ros_topics::kCameraImage, msg->header.stamp.toSec());
    pending_[target].push_back({src, msg->header.stamp.toSec(), h, {}, {}, d, {}});
    bool done = false;
    if (collect_) {
      if (collect_->started.isZero()) {
        collect_->started = msg->header.stamp;
        if (collect_->duration_s > 0.0)
          collect_->until = msg->header.stamp + ros::Duration(collect_->duration_s);
      }
      if (collect_->remaining > 0) --collect_->remaining;
      done = collect_->remaining == 0 ||
             (!collect_->until.isZero() && msg->header.stamp >= collect_->until);
    } else {
      done = static_cast<int>(pending_[target].size()) >= train_batch_;
    }
    if (done) {
      try {
        const std::string m = flush();
        ROS_INFO("histogram_place_recognizer: %s", m.c_str());
      } catch (const std::exception& e) {
        ROS_ERROR("histogram_place_recognizer: could not store training images: %s", e.what());
        pending_.clear();
      }
      collect_.reset();
    }
  }

  if (recognizer_->index().numPlaces() == 0 || recognizer_->spaces().empty()) {
    ROS_WARN_THROTTLE(30.0, "histogram_place_recognizer: the database has no trained place yet");
    diagnostics_.update();
    return;
  }
  places::PlaceResult r;
  try {
    r = recognizer_->add(h, &d);
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "histogram_place_recognizer: recognition failed: %s", e.what());
    return;
  }
  PlaceRecognition out;
  out.header = msg->header;
  const auto& names = recognizer_->index().placeNames();
  out.place = names[r.recognition.place];
  out.confidence = r.recognition.confidence;
  const bool by_histogram = r.recognition.space >= 0;
  out.method = by_histogram ? places::distanceName(r.recognition.method) : "nearest";
  out.color_space = by_histogram ? places::spaceName(r.recognition.space) : r.cue;
  out.images = static_cast<std::uint32_t>(r.images);
  out.places = names;
  out.distances = r.recognition.total_distances;
  out.belief = r.belief;
  out.filtered_place = r.filtered_place >= 0 ? names[r.filtered_place] : "";
  out.filtered_confidence = r.filtered_confidence;
  out.sequence_place = r.sequence_place >= 0 ? names[r.sequence_place] : "";
  out.route_frame = r.route_frame;
  place_pub_.publish(out);
  ++results_;
  if (!label_.empty() && label_ != "none") {
    ++labelled_;
    window_right_ += out.place == label_;
    filter_right_ += out.filtered_place == label_;
  }
  last_place_ = out.place;
  last_confidence_ = out.confidence;
  if (overlay_pub_.getNumSubscribers() > 0) publishOverlay(bgr, msg->header, out);
  diagnostics_.update();
}

void HistogramPlaceRecognizerNode::publishOverlay(const cv::Mat& bgr,
                                                  const std_msgs::Header& header,
                                                  const PlaceRecognition& r) {
  // The image (enlarged to at least 480 px wide, so the text stays legible) above a black band
  // with the window's answer and the filter's.
  const int scale_up = std::max(1, (480 + bgr.cols - 1) / bgr.cols);
  cv::Mat big;
  cv::resize(bgr, big, {}, scale_up, scale_up, cv::INTER_NEAREST);
  const int band = 100;
  cv::Mat img(big.rows + band, big.cols, CV_8UC3, cv::Scalar(0, 0, 0));
  big.copyTo(img(cv::Rect(0, 0, big.cols, big.rows)));
  char line[160];
  const double font = 0.8 * big.cols / 480.0;
  auto text = [&](int row, const cv::Scalar& colour) {
    cv::putText(img, line, {6, big.rows + 28 + 32 * row}, cv::FONT_HERSHEY_SIMPLEX, font, colour, 2,
                cv::LINE_AA);
  };
  std::snprintf(line, sizeof(line), "%s %.0f%%", r.place.c_str(), 100.0 * r.confidence);
  text(0, cv::Scalar(80, 255, 80));
  if (!r.filtered_place.empty()) {
    std::snprintf(line, sizeof(line), "fused: %s %.0f%%", r.filtered_place.c_str(),
                  100.0 * r.filtered_confidence);
    text(1, cv::Scalar(255, 200, 80));
  }
  std::snprintf(line, sizeof(line), "%s %s, %u img", r.color_space.c_str(), r.method.c_str(),
                r.images);
  text(2, cv::Scalar(200, 200, 200));
  overlay_pub_.publish(ros_conv::bgr8ToImage(img, header));
}

bool HistogramPlaceRecognizerNode::onAddImages(AddPlaceImages::Request& req,
                                               AddPlaceImages::Response& res) {
  if (req.place.empty() || req.place == "none") {
    res.success = false;
    res.message = "place must be a non-empty name other than 'none'";
    return true;
  }
  if (req.count == 0 && !(req.duration_s > 0.0)) {
    res.success = false;
    res.message = "give count > 0 or duration_s > 0";
    return true;
  }
  if (collect_) {
    res.success = false;
    res.message = "already collecting for '" + collect_->place + "'";
    return true;
  }
  Collect c;
  c.place = req.place;
  c.remaining = req.count > 0 ? static_cast<long>(req.count) : -1;
  // The time limit counts from the first collected image's stamp (bag time or wall time alike).
  c.duration_s = req.duration_s > 0.0 ? req.duration_s : 0.0;
  collect_ = c;
  res.success = true;
  res.message = "collecting images for '" + req.place + "'";
  return true;
}

bool HistogramPlaceRecognizerNode::onRemovePlace(RemovePlace::Request& req,
                                                 RemovePlace::Response& res) {
  try {
    res.success = db_->removePlace(req.place);
    res.message = res.success ? "removed '" + req.place + "'" : "no place '" + req.place + "'";
    if (res.success) reload();
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool HistogramPlaceRecognizerNode::onSetAdjacency(SetPlaceAdjacency::Request& req,
                                                  SetPlaceAdjacency::Response& res) {
  try {
    db_->setAdjacent(req.place_a, req.place_b, req.connected);
    reload();
    res.success = true;
    res.message = (req.connected ? "connected '" : "disconnected '") + req.place_a + "' and '" +
                  req.place_b + "'";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool HistogramPlaceRecognizerNode::onSave(std_srvs::Trigger::Request&,
                                          std_srvs::Trigger::Response& res) {
  try {
    res.message = flush();
    collect_.reset();
    res.success = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

void HistogramPlaceRecognizerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const auto& index = recognizer_->index();
  if (index.numPlaces() == 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no trained place");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "recognising");
  stat.add("database", db_->path());
  stat.add("places", index.numPlaces());
  stat.add("images processed", images_);
  stat.add("images dropped (bad)", bad_images_ + gate_.badImages());
  stat.add("last place", last_place_);
  stat.add("last confidence", last_confidence_);
  if (labelled_ > 0)
    stat.add("accuracy against ground_truth/place", static_cast<double>(window_right_) / labelled_);
  stat.add("mode", train_mode_ ? "train" : "recognise");
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<HistogramPlaceRecognizerNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
