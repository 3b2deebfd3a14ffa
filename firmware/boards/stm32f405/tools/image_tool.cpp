// tetrapulse-image: builds firmware images (SPEC.md §7) on the build host.
//
//   tetrapulse-image image PAYLOAD.bin LOAD_ADDRESS VERSION OUT.img
//       the 64-byte header (hw_model 1, revisions 0..255, vector_offset 0x200, payload
//       CRC-32C), zero padding to 0x200, then the payload (the linked vector table and code)
//   tetrapulse-image bundle OUT.bin IMAGE...
//       images back to back; the bootloader writes the one linked for its inactive slot
//   tetrapulse-image check IMAGE MAX_IMAGE_BYTES
//       decodes the header, checks the payload CRC and the size budget
// Numbers take C syntax (0x...). Exit status 0 on success; one line on stderr otherwise.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"

namespace {

namespace tp = tetrapulse::protocol;
constexpr uint32_t kVectorOffset = 0x200;

bool read_file(const char* path, std::vector<uint8_t>* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

bool write_file(const char* path, const std::vector<uint8_t>& data) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  return static_cast<bool>(out);
}

bool parse_u32(const char* text, uint32_t* out) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text, &end, 0);
  if (end == text || *end != '\0' || v > UINT32_MAX) return false;
  *out = static_cast<uint32_t>(v);
  return true;
}

int fail(const std::string& input, const std::string& what) {
  std::fprintf(stderr, "tetrapulse-image: %s: %s\n", input.c_str(), what.c_str());
  return 1;
}

int make_image(const char* payload_path, const char* load_text, const char* version_text,
               const char* out_path) {
  std::vector<uint8_t> payload;
  if (!read_file(payload_path, &payload)) return fail(payload_path, "cannot read");
  if (payload.empty()) return fail(payload_path, "empty payload");
  tp::ImageHeader h;
  if (!parse_u32(load_text, &h.load_address)) return fail(load_text, "not a load address");
  if (!parse_u32(version_text, &h.fw_version)) return fail(version_text, "not a version");
  h.hw_model = tp::HwModel::kStm32f405Reference;
  h.hw_revision_min = 0;
  h.hw_revision_max = 255;
  h.payload_size = static_cast<uint32_t>(payload.size());
  h.vector_offset = kVectorOffset;
  h.payload_crc32c = tp::crc32c(payload.data(), payload.size());
  std::vector<uint8_t> image(kVectorOffset, 0);
  tp::ByteWriter w(image.data(), image.size());
  const tp::Status s = tp::encode_image_header(h, w);
  if (!s) return fail(payload_path, std::string("header: ") + tp::error_name(s.error()));
  image.insert(image.end(), payload.begin(), payload.end());
  if (!write_file(out_path, image)) return fail(out_path, "cannot write");
  return 0;
}

int make_bundle(const char* out_path, int count, char** images) {
  std::vector<uint8_t> bundle;
  for (int i = 0; i < count; ++i) {
    std::vector<uint8_t> image;
    if (!read_file(images[i], &image)) return fail(images[i], "cannot read");
    const tp::Result<tp::ImageHeader> h = tp::decode_image_header(tp::ByteView{image.data(), image.size()});
    if (!h) return fail(images[i], std::string("header: ") + tp::error_name(h.error()));
    if (tp::image_size(*h) != image.size()) return fail(images[i], "size differs from its header");
    bundle.insert(bundle.end(), image.begin(), image.end());
  }
  if (!write_file(out_path, bundle)) return fail(out_path, "cannot write");
  return 0;
}

int check_image(const char* path, const char* max_text) {
  std::vector<uint8_t> image;
  if (!read_file(path, &image)) return fail(path, "cannot read");
  uint32_t max = 0;
  if (!parse_u32(max_text, &max)) return fail(max_text, "not a size");
  const tp::ByteView view{image.data(), image.size()};
  const tp::Result<tp::ImageHeader> h = tp::decode_image_header(view);
  if (!h) return fail(path, std::string("header: ") + tp::error_name(h.error()));
  if (!tp::check_payload(*h, view)) return fail(path, "payload CRC or size wrong");
  if (image.size() > max) {
    return fail(path, std::to_string(image.size()) + " bytes exceed the budget of " + std::to_string(max));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 6 && std::strcmp(argv[1], "image") == 0) return make_image(argv[2], argv[3], argv[4], argv[5]);
  if (argc >= 4 && std::strcmp(argv[1], "bundle") == 0) return make_bundle(argv[2], argc - 3, argv + 3);
  if (argc == 4 && std::strcmp(argv[1], "check") == 0) return check_image(argv[2], argv[3]);
  std::fprintf(stderr,
               "usage: tetrapulse-image image PAYLOAD LOAD_ADDRESS VERSION OUT\n"
               "       tetrapulse-image bundle OUT IMAGE...\n"
               "       tetrapulse-image check IMAGE MAX_BYTES\n");
  return 2;
}
