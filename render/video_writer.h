// SPDX-License-Identifier: MIT
#pragma once
// H.264 MP4 video through an ffmpeg child process fed raw RGB frames on a pipe. Encoded as yuv420p
// (what players accept; ffmpeg would otherwise pick 4:4:4 for RGB input), which needs even sizes.

#include <stdexcept>
#include <string>
#include <sys/types.h>

#include "render/image.h"

namespace rope::render {

struct VideoSettings {
  int width = 1280;                    // pixels, even, 2..16384
  int height = 720;                    // pixels, even, 2..16384
  int framesPerSecond = 30;            // 1..240
  int crf = 20;                        // x264 constant rate factor 0..51 (lower: better, larger)
  std::string preset = "veryfast";     // x264 preset name
  std::string ffmpegExecutable = "ffmpeg";  // a name looked up in PATH, or a path
};

// Thrown when ffmpeg cannot be found or started; PNG output does not need it.
class FfmpegNotFound : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Full path of the executable (as PATH lookup finds it), or "" if there is none.
std::string findExecutable(const std::string& name);

class VideoWriter {
 public:
  // Starts ffmpeg writing path (overwritten). Throws InvalidArgument for bad settings (odd
  // "settings.width", ...), FfmpegNotFound naming the executable and PATH if it is missing.
  VideoWriter(const std::string& path, const VideoSettings& settings);
  // Finishes the file if close() was not called; errors are swallowed here, call close() to see them.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Throws InvalidArgument("image", ...) if the size differs from the settings, std::runtime_error
  // if ffmpeg has exited (its error output is included) or after close().
  void addFrame(const Image& image);
  // Waits for ffmpeg; throws std::runtime_error with ffmpeg's exit status and error output if it
  // failed. Calling it again does nothing.
  void close();

  int frameCount() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  std::string ffmpegErrors() const;
  VideoSettings settings_;
  std::string path_;
  std::string logPath_;
  int pipe_ = -1;
  pid_t child_ = -1;
  int frames_ = 0;
};

}  // namespace rope::render
