// The host's CAN link through a fault-injecting bus (label reliability): the controller's
// error frames as SocketCAN delivers them (warning, error-passive, bus-off, restart, error
// frames of other classes), and a bus that loses frames. Every fault is one clear line,
// the link's state says what the controller is, and requests work again once it recovers.
#include <gtest/gtest.h>
#include <linux/can/error.h>

#include <cstdio>

#include "can_board_responder.hpp"
#include "fake_can_bus.hpp"
#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/can_link.hpp"

namespace tetrapulse::host {
namespace {

using testing::CanBoardResponder;
using testing::FakeCanBus;

struct Rig {
  Rig() : responder(identity()) {
    bus.attach([this](const protocol::CanFrame& f, int64_t t) { return responder.on_frame(f, t); });
    // The in-memory bus answers at once: a lost frame is known lost after 20 ms.
    BoardTimeouts timeouts;
    timeouts.request = std::chrono::milliseconds(20);
    board = std::make_unique<Board>(std::make_unique<CanLink>(bus.open(), 0, 3), timeouts);
  }
  static testing::ResponderIdentity identity() {
    testing::ResponderIdentity id;
    id.node_id = 3;
    return id;
  }
  CanLink& link() { return static_cast<CanLink&>(board->link()); }
  FakeCanBus bus;
  CanBoardResponder responder;
  std::unique_ptr<Board> board;
};

std::array<uint8_t, 8> controller(uint8_t status) { return {0, status, 0, 0, 0, 0, 0, 0}; }

TEST(CanFaults, TheControllerStateFollowsItsErrorFramesAndRequestsGoOn) {
  Rig r;
  ASSERT_TRUE(r.board->status());
  EXPECT_EQ(r.link().controller_state(), CanControllerState::kActive);
  r.bus.raise_error(CAN_ERR_CRTL, controller(CAN_ERR_CRTL_TX_WARNING));
  ASSERT_TRUE(r.board->status()) << "a warning costs nothing";
  EXPECT_EQ(r.link().controller_state(), CanControllerState::kWarning);
  r.bus.raise_error(CAN_ERR_CRTL, controller(CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE));
  r.bus.raise_error(CAN_ERR_PROT | CAN_ERR_BUSERROR);
  r.bus.raise_error(CAN_ERR_LOSTARB);
  ASSERT_TRUE(r.board->status()) << "error-passive still talks";
  EXPECT_EQ(r.link().controller_state(), CanControllerState::kPassive) << "protocol errors leave the state";
  r.bus.raise_error(CAN_ERR_CRTL, controller(CAN_ERR_CRTL_ACTIVE));
  ASSERT_TRUE(r.board->status());
  EXPECT_EQ(r.link().controller_state(), CanControllerState::kActive);
  r.bus.raise_error(CAN_ERR_BUSOFF);
  auto off = r.board->status();
  ASSERT_FALSE(off);
  std::printf("[measure] bus-off: \"%s\"\n", off.error().what().c_str());
  EXPECT_EQ(off.error().kind, HostErrorKind::kBusOff);
  EXPECT_EQ(r.link().controller_state(), CanControllerState::kBusOff);
  auto refused = r.board->info();
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().what(),
            "can:vcan0:3: get_info: the CAN controller is bus-off (restart the interface)");
  r.bus.raise_error(CAN_ERR_RESTARTED);
  r.link().receive(std::chrono::milliseconds(1));  // the answer the bus-off interrupted
  r.link().receive(std::chrono::milliseconds(1));  // the restart
  EXPECT_EQ(r.link().controller_state(), CanControllerState::kActive);
  auto again = r.board->status();
  ASSERT_TRUE(again) << again.error().what();
  EXPECT_EQ(r.link().error_frames(), 7u);
}

TEST(CanFaults, ASilenceAfterErrorFramesSaysWhatTheControllerIs) {
  FakeCanBus bus;
  CanLink link(bus.open(), 0, 4);
  bus.raise_error(CAN_ERR_CRTL, controller(CAN_ERR_CRTL_TX_PASSIVE));
  bus.raise_error(CAN_ERR_ACK);
  auto r = link.request(protocol::GetInfo{}, std::chrono::milliseconds(30));
  ASSERT_FALSE(r);
  std::printf("[measure] silence: \"%s\"\n", r.error().what().c_str());
  EXPECT_EQ(r.error().kind, HostErrorKind::kTimeout);
  EXPECT_EQ(r.error().what(),
            "can:vcan0:4: get_info: no answer within 30 ms (2 CAN error frames, the last: no acknowledgement; the"
            " controller is error-passive)");
}

TEST(CanFaults, ALossyBusCostsOnlyTheRequestsWhoseFramesItLost) {
  Rig r;
  int n = 0, lost = 0;
  // Every 7th frame on the bus vanishes (requests and answers alike).
  r.bus.lose_when([&](const protocol::CanFrame&) { return ++n % 7 == 0; });
  int ok = 0, timeouts = 0;
  for (int i = 0; i < 200; ++i) {
    auto s = r.board->status();
    if (s) {
      ++ok;
    } else {
      EXPECT_EQ(s.error().kind, HostErrorKind::kTimeout) << s.error().what();
      ++timeouts;
    }
  }
  lost = n / 7;
  std::printf("[measure] lossy bus (1 frame in 7 lost, %d lost): %d of 200 status requests answered, %d timed out\n",
              lost, ok, timeouts);
  EXPECT_GT(ok, 100);
  EXPECT_GT(timeouts, 0);
  EXPECT_EQ(ok + timeouts, 200);
}

}  // namespace
}  // namespace tetrapulse::host
