// SPDX-License-Identifier: MIT
#include "render/video_writer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>

#include "render/png_writer.h"
#include "rope/common/error.h"
#include "support/bad_settings.h"

namespace rope::render {
namespace {

// key=value lines from ffprobe for the first video stream.
std::map<std::string, std::string> probe(const std::string& path) {
  const std::string command =
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,pix_fmt,width,height,r_frame_rate,nb_read_frames -of default=noprint_wrappers=1 '" +
      path + "'";
  std::map<std::string, std::string> result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char line[256];
  while (std::fgets(line, sizeof line, pipe) != nullptr) {
    std::string text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const auto equals = text.find('=');
    if (equals != std::string::npos) result[text.substr(0, equals)] = text.substr(equals + 1);
  }
  pclose(pipe);
  return result;
}

// A moving bar, so that the encoder has something to encode.
Image testFrame(int width, int height, int index) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      const bool bar = std::abs(x - index * 8) < 10;
      p[0] = bar ? 230 : 40;
      p[1] = static_cast<std::uint8_t>(y * 255 / height);
      p[2] = 120;
    }
  }
  return image;
}

TEST(VideoWriter, EncodesH264Yuv420pWithTheRequestedRateSizeAndFrameCount) {
  if (findExecutable("ffmpeg").empty() || findExecutable("ffprobe").empty()) GTEST_SKIP() << "ffmpeg not installed";
  const std::string path = ::testing::TempDir() + "splinerope_video_test.mp4";
  VideoSettings settings;
  settings.width = 320;
  settings.height = 240;
  settings.framesPerSecond = 24;
  {
    VideoWriter video(path, settings);
    for (int i = 0; i < 12; ++i) video.addFrame(testFrame(320, 240, i));
    EXPECT_EQ(video.frameCount(), 12);
    video.close();
    video.close();  // a second close does nothing
  }
  const auto info = probe(path);
  EXPECT_EQ(info.at("codec_name"), "h264");
  EXPECT_EQ(info.at("pix_fmt"), "yuv420p");
  EXPECT_EQ(info.at("width"), "320");
  EXPECT_EQ(info.at("height"), "240");
  EXPECT_EQ(info.at("r_frame_rate"), "24/1");
  EXPECT_EQ(info.at("nb_read_frames"), "12");
  std::remove(path.c_str());
}

TEST(VideoWriter, DestructorFinishesTheFile) {
  if (findExecutable("ffmpeg").empty() || findExecutable("ffprobe").empty()) GTEST_SKIP() << "ffmpeg not installed";
  const std::string path = ::testing::TempDir() + "splinerope_video_destructor.mp4";
  VideoSettings settings;
  settings.width = 64;
  settings.height = 48;
  {
    VideoWriter video(path, settings);
    for (int i = 0; i < 5; ++i) video.addFrame(testFrame(64, 48, i));
  }
  EXPECT_EQ(probe(path).at("nb_read_frames"), "5");
  std::remove(path.c_str());
}

TEST(VideoWriter, MissingFfmpegIsAClearErrorAndPngStillWorks) {
  VideoSettings settings;
  settings.width = 64;
  settings.height = 48;
  settings.ffmpegExecutable = "splinerope-no-such-ffmpeg";
  try {
    VideoWriter video(::testing::TempDir() + "never.mp4", settings);
    FAIL();
  } catch (const FfmpegNotFound& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("ffmpeg"), std::string::npos);
    EXPECT_NE(message.find("splinerope-no-such-ffmpeg"), std::string::npos);
  }
  settings.ffmpegExecutable = "/nonexistent/bin/ffmpeg";
  EXPECT_THROW(VideoWriter(::testing::TempDir() + "never.mp4", settings), FfmpegNotFound);
  const std::string png = ::testing::TempDir() + "splinerope_frame_without_ffmpeg.png";
  EXPECT_NO_THROW(writePng(png, testFrame(64, 48, 0)));
  std::remove(png.c_str());
}

TEST(VideoWriter, RejectsOddSizesAndBadSettings) {
  using S = VideoSettings;
  rope::test::expectEachRejected<S>({{"settings.width", [](S& s) { s.width = 641; }},
                                     {"settings.height", [](S& s) { s.height = 479; }},
                                     {"settings.height", [](S& s) { s.height = 0; }},
                                     {"settings.framesPerSecond", [](S& s) { s.framesPerSecond = 0; }},
                                     {"settings.crf", [](S& s) { s.crf = 52; }}},
                                    [](const S& settings) { VideoWriter video(::testing::TempDir() + "never.mp4", settings); });
}

TEST(VideoWriter, WrongFrameSizeAndFfmpegFailuresAreReported) {
  if (findExecutable("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg not installed";
  VideoSettings settings;
  settings.width = 64;
  settings.height = 48;
  const std::string path = ::testing::TempDir() + "splinerope_video_sizes.mp4";
  {
    VideoWriter video(path, settings);
    try {
      video.addFrame(testFrame(66, 48, 0));
      FAIL();
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.parameter(), "image");
    }
    EXPECT_EQ(video.frameCount(), 0);
    video.close();
    EXPECT_THROW(video.addFrame(testFrame(64, 48, 0)), std::runtime_error);
  }
  std::remove(path.c_str());
  // ffmpeg cannot create the output: the failure (with ffmpeg's reason) surfaces as an exception
  // from addFrame or close, never as a crash from SIGPIPE.
  bool reported = false;
  try {
    VideoWriter video("/nonexistent-directory/out.mp4", settings);
    for (int i = 0; i < 200; ++i) video.addFrame(testFrame(64, 48, i));
    video.close();
  } catch (const std::runtime_error& e) {
    reported = std::string(e.what()).find("ffmpeg") != std::string::npos;
  }
  EXPECT_TRUE(reported);
}

}  // namespace
}  // namespace rope::render
