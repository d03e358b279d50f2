#include "adaptive_perception/color/color_space.h"

#include <gtest/gtest.h>

using namespace adaptive_perception::color;

TEST(ColorSpace, KnownBt601Values) {
  // White, black and pure red in BT.601 full range.
  EXPECT_NEAR((rgbToYuv({255, 255, 255}) - Eigen::Vector3d(255, 128, 128)).norm(), 0.0, 1e-3);
  EXPECT_NEAR((rgbToYuv({0, 0, 0}) - Eigen::Vector3d(0, 128, 128)).norm(), 0.0, 1e-9);
  const Eigen::Vector3d red = rgbToYuv({255, 0, 0});
  EXPECT_NEAR(red[0], 76.245, 1e-3);
  EXPECT_NEAR(red[1], 84.97, 0.01);
  EXPECT_NEAR(red[2], 255.5, 0.01);
}

TEST(ColorSpace, RoundTrip) {
  for (double r : {0.0, 37.0, 200.0})
    for (double g : {5.0, 128.0, 255.0})
      for (double b : {0.0, 90.0, 250.0}) {
        const Eigen::Vector3d rgb(r, g, b);
        EXPECT_LT((yuvToRgb(rgbToYuv(rgb)) - rgb).norm(), 0.01);
      }
}

TEST(ColorSpace, UyvyPacksPairsAndUnpacks) {
  cv::Mat y(1, 4, CV_32F), u(1, 4, CV_32F), v(1, 4, CV_32F);
  y.at<float>(0) = 10;
  y.at<float>(1) = 20;
  y.at<float>(2) = 300;
  y.at<float>(3) = -5;
  u.at<float>(0) = 100;
  u.at<float>(1) = 110;
  u.at<float>(2) = 50;
  u.at<float>(3) = 50;
  v.at<float>(0) = 130;
  v.at<float>(1) = 140;
  v.at<float>(2) = 0;
  v.at<float>(3) = 2;
  const cv::Mat p = packUyvy(y, u, v);
  ASSERT_EQ(p.type(), CV_8UC2);
  const std::uint8_t* b = p.ptr<std::uint8_t>(0);
  const std::uint8_t expect[8] = {105, 10, 135, 20, 50, 255, 1, 0};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(b[i], expect[i]) << i;
  const cv::Mat yuv = unpackUyvy(p);
  EXPECT_EQ(yuv.at<cv::Vec3b>(0, 1), cv::Vec3b(20, 105, 135));
  EXPECT_EQ(yuv.at<cv::Vec3b>(0, 2), cv::Vec3b(255, 50, 1));
  cv::Mat odd(1, 3, CV_32F);
  EXPECT_THROW(packUyvy(odd, odd, odd), std::invalid_argument);
}

TEST(ColorSpace, UyvyToBgrOfGrey) {
  cv::Mat y(2, 2, CV_32F, cv::Scalar(100)), uv(2, 2, CV_32F, cv::Scalar(128));
  const cv::Mat bgr = uyvyToBgr(packUyvy(y, uv, uv));
  EXPECT_EQ(bgr.at<cv::Vec3b>(1, 1), cv::Vec3b(100, 100, 100));
}
