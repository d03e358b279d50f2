#pragma once
// A simulated camera's sensor response, shared by the field camera (sim/camera_sensor.h: the
// AIBO's CMOS, which delivers YUV, so its noise is added to the luminance) and the indoor camera
// (sim/indoor_renderer.h: an RGB camera with auto-exposure, noise in each channel): white balance
// fixed for one colour temperature, vignetting, a gamma curve to 8-bit levels, and
// signal-dependent noise. What differs between the two cameras (chroma noise and chroma
// vignetting of the YUV sensor, auto-exposure of the RGB one) stays in their own configs.
namespace adaptive_perception::sim {

struct SensorResponse {
  double white_point_k = 5000.0;  // white balance fixed for this colour temperature, K
  double vignetting = 0.25;       // relative luminance loss at the image corners, [0, 1)
  double gamma = 2.2;             // level = 255 linear^(1/gamma), 0.5..4
  double read_noise = 1.5;        // noise at level 0, 8-bit levels (standard deviation)
  double shot_noise = 0.05;       // noise variance per level of signal

  /// Throws std::invalid_argument naming the first field out of range.
  void validate() const;
  /// Relative luminance at squared normalised radius r2 (0: the centre, 1: the corners).
  double falloff(double r2) const { return 1.0 - vignetting * r2; }
  /// The 8-bit level of a linear value: 255 clamp(linear, 0, 1)^(1/gamma).
  double level(double linear) const;
  /// The noise's standard deviation at a level: sqrt(read_noise^2 + shot_noise max(level, 0)).
  double noiseSd(double level) const;
};

}  // namespace adaptive_perception::sim
