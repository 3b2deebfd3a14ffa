#pragma once
// A Cyclone DDS entity handle that deletes its entity (and every child) when it goes.
#include <utility>

#include <dds/dds.h>

namespace tetrapulse::ros2 {

class DdsEntity {
 public:
  DdsEntity() = default;
  explicit DdsEntity(dds_entity_t handle) : handle_(handle) {}
  DdsEntity(DdsEntity&& o) noexcept : handle_(std::exchange(o.handle_, 0)) {}
  DdsEntity& operator=(DdsEntity&& o) noexcept {
    if (this != &o) {
      reset();
      handle_ = std::exchange(o.handle_, 0);
    }
    return *this;
  }
  DdsEntity(const DdsEntity&) = delete;
  DdsEntity& operator=(const DdsEntity&) = delete;
  ~DdsEntity() { reset(); }

  dds_entity_t get() const { return handle_; }
  void reset() {
    if (handle_ > 0) dds_delete(handle_);
    handle_ = 0;
  }

 private:
  dds_entity_t handle_ = 0;
};

}  // namespace tetrapulse::ros2
