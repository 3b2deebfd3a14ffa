// usb_echo_probe: the host half of the VM's USB self-test. Opens VID:PID with
// libusb-1.0, finds the vendor-specific interface and its bulk endpoints in the
// configuration descriptor (the UDC renumbers endpoints, so addresses are never
// assumed), and round-trips random payloads through the ffs_selftest echo.
// Sizes straddle the packet size; a transfer that fills whole packets is ended
// with a zero-length packet so the gadget sees where it stops.
//
// usage: usb_echo_probe VID:PID      (hex, e.g. 1209:0001)

#include <libusb-1.0/libusb.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr unsigned kTimeoutMs = 5000;

struct BulkPair {
  int interface = -1;
  uint8_t out = 0;
  uint8_t in = 0;
};

// The first vendor-specific interface with a bulk OUT and a bulk IN endpoint.
BulkPair FindBulkPair(libusb_device* device) {
  BulkPair pair;
  libusb_config_descriptor* config = nullptr;
  if (libusb_get_active_config_descriptor(device, &config) != 0) return pair;
  for (int i = 0; i < config->bNumInterfaces && pair.interface < 0; ++i) {
    const libusb_interface& interface = config->interface[i];
    if (interface.num_altsetting < 1) continue;
    const libusb_interface_descriptor& alt = interface.altsetting[0];
    if (alt.bInterfaceClass != LIBUSB_CLASS_VENDOR_SPEC) continue;
    BulkPair candidate;
    candidate.interface = alt.bInterfaceNumber;
    for (int e = 0; e < alt.bNumEndpoints; ++e) {
      const libusb_endpoint_descriptor& ep = alt.endpoint[e];
      if ((ep.bmAttributes & LIBUSB_TRANSFER_TYPE_MASK) != LIBUSB_TRANSFER_TYPE_BULK) continue;
      if ((ep.bEndpointAddress & LIBUSB_ENDPOINT_DIR_MASK) == LIBUSB_ENDPOINT_IN) {
        candidate.in = ep.bEndpointAddress;
      } else {
        candidate.out = ep.bEndpointAddress;
      }
    }
    if (candidate.in != 0 && candidate.out != 0) pair = candidate;
  }
  libusb_free_config_descriptor(config);
  return pair;
}

bool ParseIds(const std::string& text, uint16_t* vid, uint16_t* pid) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) return false;
  char* end = nullptr;
  const unsigned long v = std::strtoul(text.c_str(), &end, 16);
  if (end != text.c_str() + colon || v > 0xFFFF) return false;
  const unsigned long p = std::strtoul(text.c_str() + colon + 1, &end, 16);
  if (*end != '\0' || p > 0xFFFF) return false;
  *vid = static_cast<uint16_t>(v);
  *pid = static_cast<uint16_t>(p);
  return true;
}

// Sends `payload` and reads back as many bytes; true when they are equal.
bool RoundTrip(libusb_device_handle* handle, const BulkPair& pair, int max_packet, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> sent = payload;
  int done = 0;
  int rc = libusb_bulk_transfer(handle, pair.out, sent.data(), static_cast<int>(sent.size()), &done, kTimeoutMs);
  if (rc != 0 || done != static_cast<int>(sent.size())) {
    std::fprintf(stderr, "usb_echo_probe: writing %zu bytes to 0x%02x: %s (%d written)\n", sent.size(), pair.out,
                 libusb_error_name(rc), done);
    return false;
  }
  if (sent.size() % static_cast<size_t>(max_packet) == 0) {
    rc = libusb_bulk_transfer(handle, pair.out, sent.data(), 0, &done, kTimeoutMs);
    if (rc != 0) {
      std::fprintf(stderr, "usb_echo_probe: zero-length packet to 0x%02x: %s\n", pair.out, libusb_error_name(rc));
      return false;
    }
  }
  std::vector<uint8_t> received(payload.size());
  rc = libusb_bulk_transfer(handle, pair.in, received.data(), static_cast<int>(received.size()), &done, kTimeoutMs);
  if (rc != 0 || done != static_cast<int>(received.size())) {
    std::fprintf(stderr, "usb_echo_probe: reading %zu bytes from 0x%02x: %s (%d read)\n", received.size(), pair.in,
                 libusb_error_name(rc), done);
    return false;
  }
  if (received != payload) {
    size_t first = 0;
    while (received[first] == payload[first]) ++first;
    std::fprintf(stderr, "usb_echo_probe: %zu-byte echo differs from what was sent, first at byte %zu\n",
                 payload.size(), first);
    return false;
  }
  return true;
}

int Probe(libusb_context* context, uint16_t vid, uint16_t pid) {
  // Enumeration under TCG can lag the gadget's bind by a few seconds.
  libusb_device_handle* handle = nullptr;
  for (int attempt = 0; attempt < 100 && handle == nullptr; ++attempt) {
    handle = libusb_open_device_with_vid_pid(context, vid, pid);
    if (handle == nullptr) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (handle == nullptr) {
    std::fprintf(stderr, "usb_echo_probe: no device %04x:%04x could be opened within 10 s\n", vid, pid);
    return 1;
  }
  const BulkPair pair = FindBulkPair(libusb_get_device(handle));
  if (pair.interface < 0) {
    std::fprintf(stderr, "usb_echo_probe: %04x:%04x has no vendor interface with bulk IN and OUT\n", vid, pid);
    libusb_close(handle);
    return 1;
  }
  const int max_packet = libusb_get_max_packet_size(libusb_get_device(handle), pair.out);
  std::printf("usb_echo_probe: interface %d, bulk OUT 0x%02x, bulk IN 0x%02x, max packet %d (from the config descriptor)\n",
              pair.interface, pair.out, pair.in, max_packet);
  if (max_packet <= 0 || libusb_claim_interface(handle, pair.interface) != 0) {
    std::fprintf(stderr, "usb_echo_probe: cannot claim interface %d\n", pair.interface);
    libusb_close(handle);
    return 1;
  }
  std::mt19937 random(0x7e7a);
  const std::vector<size_t> sizes = {1, 63, 64, 65, 511, 512, 513, 1000, 4096, 16384};
  int failures = 0;
  for (const size_t size : sizes) {
    std::vector<uint8_t> payload(size);
    for (uint8_t& byte : payload) byte = static_cast<uint8_t>(random());
    if (!RoundTrip(handle, pair, max_packet, payload)) ++failures;
  }
  libusb_release_interface(handle, pair.interface);
  libusb_close(handle);
  if (failures != 0) {
    std::fprintf(stderr, "usb_echo_probe: %d of %zu echoes failed\n", failures, sizes.size());
    return 1;
  }
  std::printf("usb_echo_probe: %zu echoes of 1..16384 bytes came back intact\n", sizes.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  uint16_t vid = 0;
  uint16_t pid = 0;
  if (argc != 2 || !ParseIds(argv[1], &vid, &pid)) {
    std::fprintf(stderr, "usage: usb_echo_probe VID:PID   (hex, e.g. 1209:0001)\n");
    return 2;
  }
  libusb_context* context = nullptr;
  const int rc = libusb_init(&context);
  if (rc != 0) {
    std::fprintf(stderr, "usb_echo_probe: libusb_init: %s\n", libusb_error_name(rc));
    return 1;
  }
  const int status = Probe(context, vid, pid);
  libusb_exit(context);
  return status;
}
