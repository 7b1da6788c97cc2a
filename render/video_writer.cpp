// SPDX-License-Identifier: MIT
#include "render/video_writer.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <vector>

#include "rope/common/error.h"

extern char** environ;

namespace rope::render {

namespace {

bool isExecutableFile(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// Writes all bytes, with SIGPIPE blocked for this thread so that a dead ffmpeg turns into EPIPE
// (an error we report) instead of killing the whole program; a SIGPIPE raised meanwhile is
// consumed before the mask is restored. Returns 0 or the errno of the failed write.
int writeAll(int fd, const std::uint8_t* data, std::size_t size) {
  sigset_t pipeSignal, previous;
  sigemptyset(&pipeSignal);
  sigaddset(&pipeSignal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipeSignal, &previous);
  int error = 0;
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      error = errno;
      break;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  if (error == EPIPE) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipeSignal, nullptr, &zero) > 0) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return error;
}

std::string describeStatus(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

}  // namespace

std::string findExecutable(const std::string& name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string::npos) return isExecutableFile(name) ? name : "";
  const char* path = std::getenv("PATH");
  std::stringstream directories(path != nullptr ? path : "");
  std::string directory;
  while (std::getline(directories, directory, ':')) {
    const std::string candidate = (directory.empty() ? std::string(".") : directory) + "/" + name;
    if (isExecutableFile(candidate)) return candidate;
  }
  return "";
}

VideoWriter::VideoWriter(const std::string& path, const VideoSettings& settings) : settings_(settings), path_(path) {
  auto requireEvenSize = [](const char* parameter, int value) {
    if (value < 2 || value > 16384 || value % 2 != 0) {
      throw InvalidArgument(parameter, std::to_string(value),
                            "must be even and within [2, 16384] (H.264 with yuv420p halves the chroma resolution)");
    }
  };
  requireEvenSize("settings.width", settings.width);
  requireEvenSize("settings.height", settings.height);
  if (settings.framesPerSecond < 1 || settings.framesPerSecond > 240) {
    throw InvalidArgument("settings.framesPerSecond", std::to_string(settings.framesPerSecond), "must be within [1, 240]");
  }
  if (settings.crf < 0 || settings.crf > 51) {
    throw InvalidArgument("settings.crf", std::to_string(settings.crf), "must be within [0, 51]");
  }
  if (settings.preset.empty()) throw InvalidArgument("settings.preset", "\"\"", "must name an x264 preset");
  if (path.empty()) throw InvalidArgument("path", "\"\"", "must name the output file");
  const std::string executable = findExecutable(settings.ffmpegExecutable);
  if (executable.empty()) {
    const char* searchPath = std::getenv("PATH");
    throw FfmpegNotFound("video output needs ffmpeg, but \"" + settings.ffmpegExecutable +
                         "\" was not found (PATH=" + (searchPath != nullptr ? searchPath : "") +
                         "); install ffmpeg (Debian: apt-get install ffmpeg) or write PNG frames instead");
  }

  // ffmpeg's diagnostics go to a temporary file so that a failure can be reported with its reason.
  char logTemplate[] = "/tmp/splinerope_ffmpeg_XXXXXX";
  const int logFd = ::mkstemp(logTemplate);
  if (logFd < 0) throw std::runtime_error(std::string("VideoWriter: cannot create a log file: ") + std::strerror(errno));
  logPath_ = logTemplate;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    ::close(logFd);
    ::unlink(logPath_.c_str());
    throw std::runtime_error(std::string("VideoWriter: pipe failed: ") + std::strerror(errno));
  }
  const std::string size = std::to_string(settings.width) + "x" + std::to_string(settings.height);
  const std::string fps = std::to_string(settings.framesPerSecond);
  const std::string crf = std::to_string(settings.crf);
  std::vector<std::string> arguments{executable, "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                                     "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", size, "-r", fps, "-i", "pipe:0",
                                     "-an", "-c:v", "libx264", "-preset", settings.preset, "-crf", crf,
                                     "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", path};
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, logFd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, logFd, STDERR_FILENO);
  const int spawned = ::posix_spawn(&child_, executable.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  ::close(logFd);
  if (spawned != 0) {
    ::close(fds[1]);
    ::unlink(logPath_.c_str());
    child_ = -1;
    throw FfmpegNotFound("VideoWriter: cannot start " + executable + ": " + std::strerror(spawned));
  }
  pipe_ = fds[1];
}

VideoWriter::~VideoWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Reported only through an explicit close(), as documented.
  }
}

std::string VideoWriter::ffmpegErrors() const {
  std::ifstream log(logPath_);
  std::stringstream text;
  text << log.rdbuf();
  std::string result = text.str();
  if (result.size() > 2000) result = result.substr(result.size() - 2000);
  return result.empty() ? "(no output)" : result;
}

void VideoWriter::addFrame(const Image& image) {
  if (pipe_ < 0) throw std::runtime_error("VideoWriter::addFrame: " + path_ + " is already closed");
  if (image.width != settings_.width || image.height != settings_.height ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3) {
    throw InvalidArgument("image", std::to_string(image.width) + "x" + std::to_string(image.height),
                          "must match the video size " + std::to_string(settings_.width) + "x" +
                              std::to_string(settings_.height));
  }
  if (const int error = writeAll(pipe_, image.pixels.data(), image.pixels.size()); error != 0) {
    const std::string reason = std::strerror(error);
    close();  // throws with ffmpeg's own message if it failed
    throw std::runtime_error("VideoWriter: writing a frame to ffmpeg failed: " + reason);
  }
  ++frames_;
}

void VideoWriter::close() {
  if (child_ < 0) return;
  if (pipe_ >= 0) {
    ::close(pipe_);
    pipe_ = -1;
  }
  int status = 0;
  pid_t waited;
  do {
    waited = ::waitpid(child_, &status, 0);
  } while (waited < 0 && errno == EINTR);
  child_ = -1;
  const std::string errors = ffmpegErrors();
  ::unlink(logPath_.c_str());
  if (waited < 0) throw std::runtime_error("VideoWriter: waitpid for ffmpeg failed: " + std::string(std::strerror(errno)));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("VideoWriter: ffmpeg failed writing " + path_ + " (" + describeStatus(status) + "): " +
                             errors);
  }
}

}  // namespace rope::render
