#pragma once
// What the vivid probes share: V4L2 ioctls that name their failure, controls and
// menu items found by name (vivid's controls are driver-private: no fixed ids to
// rely on across kernels), inputs and outputs selected by name, and clocks.
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <time.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <string>

namespace probe {

[[noreturn]] inline void die(const std::string& what) {
  std::fprintf(stderr, "%s\n", what.c_str());
  std::exit(1);
}

// `--key value` pairs after argv[first].
inline std::map<std::string, std::string> parse_options(int argc, char** argv, int first, const std::string& program) {
  std::map<std::string, std::string> a;
  for (int i = first; i < argc; i += 2) {
    if (std::strncmp(argv[i], "--", 2) != 0 || i + 1 >= argc) die(program + ": expected --option value, got " + argv[i]);
    a[argv[i] + 2] = argv[i + 1];
  }
  return a;
}

inline std::string need(const std::map<std::string, std::string>& a, const std::string& key, const std::string& program) {
  auto it = a.find(key);
  if (it == a.end()) die(program + ": --" + key + " is required");
  return it->second;
}

inline int xioctl(int fd, unsigned long request, void* arg) {
  int r = 0;
  do r = ioctl(fd, request, arg);
  while (r < 0 && errno == EINTR);
  return r;
}

// The ioctl or die naming the device and the request.
inline void must(int fd, unsigned long request, void* arg, const std::string& device, const char* what) {
  if (xioctl(fd, request, arg) < 0) die(device + ": " + what + ": " + std::strerror(errno));
}

inline int64_t monotonic_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

inline void sleep_until_ns(int64_t ns) {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  t.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
  }
}

inline std::optional<v4l2_query_ext_ctrl> find_control(int fd, const std::string& name) {
  v4l2_query_ext_ctrl q{};
  q.id = V4L2_CTRL_FLAG_NEXT_CTRL | V4L2_CTRL_FLAG_NEXT_COMPOUND;
  while (xioctl(fd, VIDIOC_QUERY_EXT_CTRL, &q) == 0) {
    if (name == q.name) return q;
    q.id |= V4L2_CTRL_FLAG_NEXT_CTRL | V4L2_CTRL_FLAG_NEXT_COMPOUND;
  }
  return std::nullopt;
}

// Sets the menu control `name` to the item called `item`.
inline void set_menu(int fd, const std::string& device, const std::string& name, const std::string& item) {
  auto c = find_control(fd, name);
  if (!c) die(device + ": no control \"" + name + "\"");
  if (c->type != V4L2_CTRL_TYPE_MENU) die(device + ": control \"" + name + "\" is not a menu");
  for (int64_t i = c->minimum; i <= c->maximum; ++i) {
    v4l2_querymenu m{};
    m.id = c->id;
    m.index = static_cast<uint32_t>(i);
    if (xioctl(fd, VIDIOC_QUERYMENU, &m) < 0) continue;
    if (item == reinterpret_cast<const char*>(m.name)) {
      v4l2_control v{};
      v.id = c->id;
      v.value = static_cast<int32_t>(i);
      must(fd, VIDIOC_S_CTRL, &v, device, ("VIDIOC_S_CTRL \"" + name + "\"").c_str());
      return;
    }
  }
  die(device + ": control \"" + name + "\" has no item \"" + item + "\"");
}

// Selects the first input (v4l2_input, VIDIOC_ENUMINPUT / VIDIOC_S_INPUT) or output
// (v4l2_output, VIDIOC_ENUMOUTPUT / VIDIOC_S_OUTPUT) whose name starts with `prefix`.
template <typename Port>
void select_port(int fd, const std::string& device, const std::string& prefix, unsigned long enumerate,
                 unsigned long select, const char* what) {
  for (uint32_t i = 0;; ++i) {
    Port port{};
    port.index = i;
    if (xioctl(fd, enumerate, &port) < 0) break;
    if (std::string(reinterpret_cast<const char*>(port.name)).rfind(prefix, 0) == 0) {
      int index = static_cast<int>(i);
      must(fd, select, &index, device, what);
      return;
    }
  }
  die(device + ": no " + (enumerate == VIDIOC_ENUMINPUT ? "input" : "output") + " named " + prefix + "...");
}

inline void select_input(int fd, const std::string& device, const std::string& prefix) {
  select_port<v4l2_input>(fd, device, prefix, VIDIOC_ENUMINPUT, VIDIOC_S_INPUT, "VIDIOC_S_INPUT");
}

inline void select_output(int fd, const std::string& device, const std::string& prefix) {
  select_port<v4l2_output>(fd, device, prefix, VIDIOC_ENUMOUTPUT, VIDIOC_S_OUTPUT, "VIDIOC_S_OUTPUT");
}

inline std::string fourcc_text(uint32_t f) {
  return std::string{static_cast<char>(f & 0xff), static_cast<char>((f >> 8) & 0xff), static_cast<char>((f >> 16) & 0xff),
                     static_cast<char>((f >> 24) & 0xff)};
}

}  // namespace probe
