// libFuzzer: message bytes into the command handler of a simulated board. Nothing may
// crash; every answer must decode; an input that does not decode changes nothing but the
// diagnostic counters. The board lives across inputs, so sequences of requests (an update
// begun, a config set) build up state for later inputs to meet.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "tetrapulse/fw/app/firmware.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace {

using namespace tetrapulse;

sim_board::SimBoard& board() {
  static sim_board::SimBoard* b = [] {
    sim_board::SimBoardOptions o;
    o.clock_ppm = 37;
    return new sim_board::SimBoard(o);
  }();
  return *b;
}

std::vector<uint8_t> config_bytes(const fw::Firmware& f) {
  uint8_t buf[protocol::kConfigSize];
  protocol::ByteWriter w(buf, sizeof(buf));
  (void)protocol::encode_config(f.board().config(), w);
  return std::vector<uint8_t>(buf, buf + w.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sim_board::SimBoard& b = board();
  if (b.firmware() == nullptr) b.power_cycle();  // a Reboot{bootloader} earlier
  b.advance_to(b.now() + 1'000'000);
  fw::Firmware& f = *b.firmware();
  const bool decodes = protocol::decode(protocol::ByteView{data, size}).ok();
  const std::vector<uint8_t> flash_before = b.flash().contents();
  const std::vector<uint8_t> config_before = config_bytes(f);
  const protocol::UpdateState update_before = f.board().update().state();

  uint8_t out[protocol::kMaxMessageSize];
  const fw::CommandReply reply = f.handle(protocol::ByteView{data, size}, b.tick(), fw::LinkKind::kCan, out, sizeof(out));
  if (reply.size > 0 && !protocol::decode(protocol::ByteView{out, reply.size}).ok()) std::abort();
  if (!decodes) {
    if (b.flash().contents() != flash_before || config_bytes(f) != config_before ||
        f.board().update().state() != update_before || reply.reboot) {
      std::abort();
    }
  }
  if (reply.reboot) b.power_cycle();
  return 0;
}
