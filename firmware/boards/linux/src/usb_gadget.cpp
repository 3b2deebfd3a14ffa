#include "tetrapulse/linux_board/usb_gadget.hpp"

#include <dirent.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace tp = protocol;
const std::string kGadgetRoot = "/sys/kernel/config/usb_gadget/";

std::string hex4(uint16_t v) {
  char text[8];
  std::snprintf(text, sizeof(text), "0x%04x", v);
  return text;
}

tl::unexpected<BoardError> gadget_error(std::string where, std::string message) {
  return board_error(BoardErrorKind::kUsbGadget, std::move(where), std::move(message));
}

// Writes `value` to a configfs attribute.
BoardResult<void> put(const std::string& path, const std::string& value) {
  std::ofstream out(path);
  out << value << '\n';
  out.flush();
  if (!out) return gadget_error(path, "cannot write '" + value + "'");
  return {};
}

BoardResult<void> make_dir(const std::string& path) {
  if (::mkdir(path.c_str(), 0755) != 0 && errno != EEXIST) return gadget_error(path, std::strerror(errno));
  return {};
}

std::string first_udc() {
  DIR* d = ::opendir("/sys/class/udc");
  if (d == nullptr) return {};
  std::string name;
  while (dirent* e = ::readdir(d)) {
    if (e->d_name[0] != '.') {
      name = e->d_name;
      break;
    }
  }
  ::closedir(d);
  return name;
}

}  // namespace

BoardResult<void> UsbGadget::create(const UsbGadgetSpec& spec) {
  spec_ = spec;
  remove();
  const std::string g = kGadgetRoot + spec.name;
  const std::string function = g + "/functions/ffs." + spec.name;
  const uint16_t pid =
      spec.mode == tp::UsbMode::kApplication ? tp::kUsbProductIdApplication : tp::kUsbProductIdBootloader;
  struct stat st{};
  if (::stat(kGadgetRoot.c_str(), &st) != 0) {
    return gadget_error("", kGadgetRoot + " is missing: mount configfs and load libcomposite and usb_f_fs");
  }
  for (const BoardResult<void>& step :
       {make_dir(g), put(g + "/idVendor", hex4(tp::kUsbVendorId)), put(g + "/idProduct", hex4(pid)),
        put(g + "/bcdDevice", hex4(spec.bcd_device)), put(g + "/bcdUSB", "0x0200"), make_dir(g + "/strings/0x409"),
        put(g + "/strings/0x409/manufacturer", tp::kUsbManufacturerString),
        put(g + "/strings/0x409/product", tp::kUsbProductString), put(g + "/strings/0x409/serialnumber", spec.serial),
        make_dir(g + "/configs/c.1"), put(g + "/configs/c.1/MaxPower", "100"), make_dir(function)}) {
    if (!step) return step;
  }
  if (::symlink(function.c_str(), (g + "/configs/c.1/ffs." + spec.name).c_str()) != 0 && errno != EEXIST) {
    return gadget_error(g + "/configs/c.1", std::string("cannot link the function: ") + std::strerror(errno));
  }
  std::error_code made;
  std::filesystem::create_directories(spec.mount_dir, made);
  if (made) return gadget_error(spec.mount_dir, made.message());
  if (::mount(spec.name.c_str(), spec.mount_dir.c_str(), "functionfs", 0, nullptr) != 0) {
    return gadget_error("", "mount functionfs " + spec.name + " at " + spec.mount_dir + ": " + std::strerror(errno));
  }
  return {};
}

BoardResult<void> UsbGadget::bind() {
  const std::string udc = spec_.udc.empty() ? first_udc() : spec_.udc;
  if (udc.empty()) return gadget_error("", "no USB device controller in /sys/class/udc (load dummy_hcd, or a UDC driver)");
  return put(kGadgetRoot + spec_.name + "/UDC", udc);
}

void UsbGadget::remove() {
  if (spec_.name.empty()) return;
  const std::string g = kGadgetRoot + spec_.name;
  struct stat st{};
  if (::stat(g.c_str(), &st) == 0) {
    static_cast<void>(put(g + "/UDC", ""));
    ::unlink((g + "/configs/c.1/ffs." + spec_.name).c_str());
  }
  ::umount2(spec_.mount_dir.c_str(), MNT_DETACH);
  for (const std::string& dir : {g + "/configs/c.1/strings/0x409", g + "/configs/c.1", g + "/functions/ffs." + spec_.name,
                                 g + "/strings/0x409", g}) {
    ::rmdir(dir.c_str());
  }
}

}  // namespace tetrapulse::linux_board
