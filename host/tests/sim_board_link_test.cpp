// Board calls and a firmware update against the simulated board (firmware/boards/sim, the
// real firmware core) through SimLink: the host driver and the board code agree.
#include <gtest/gtest.h>

#include "tetrapulse/host/firmware_update.hpp"
#include "tetrapulse/host/sim_board_link.hpp"
#include "tetrapulse/sim_board/sim_image.hpp"

namespace tetrapulse::host {
namespace {

struct SimRig {
  std::shared_ptr<sim_board::SimBoard> sim;
  std::unique_ptr<Board> board;
  explicit SimRig(uint8_t node = 4) {
    sim_board::SimBoardOptions o;
    o.node_id = node;
    o.serial[11] = node;
    sim = std::make_shared<sim_board::SimBoard>(o);
    sim->advance_to(1'000'000);
    board = std::make_unique<Board>(std::make_unique<SimLink>("sim:4", sim_board_port(sim)));
  }
};

TEST(SimBoardLink, InfoConfigAndStatusFromTheFirmwareCore) {
  SimRig rig;
  auto info = rig.board->info();
  ASSERT_TRUE(info) << info.error().what();
  EXPECT_EQ(info->hw_model, protocol::HwModel::kSimulatedBoard);
  EXPECT_EQ(info->node_id, 4);
  EXPECT_EQ(info->serial[11], 4);
  protocol::Config c;
  c.node_id = 4;
  c.codes[0] = protocol::Code{8, 0xB5};
  c.bit_period_ns = 2'000'000;
  ASSERT_TRUE(rig.board->configure(c));
  auto back = rig.board->config();
  ASSERT_TRUE(back) << back.error().what();
  EXPECT_EQ(back->codes[0].bits, 0xB5u);
  EXPECT_EQ(back->bit_period_ns, 2'000'000u);
  ASSERT_TRUE(rig.board->persist());
  auto status = rig.board->status();
  ASSERT_TRUE(status) << status.error().what();
  EXPECT_EQ(status->update_state, protocol::UpdateState::kIdle);
}

TEST(SimBoardLink, UpdatesTheSimulatedBoardToANewVersion) {
  SimRig rig;
  auto info = rig.board->info();
  ASSERT_TRUE(info);
  sim_board::SimImageSpec spec;
  spec.fw_version = 0x01040000;
  spec.payload_size = 5000;
  auto image = check_firmware_image(sim_board::make_sim_image(spec), "sim-1.4.0.bin");
  ASSERT_TRUE(image) << image.error().what();
  const std::vector<FirmwareImage> images{*image};
  auto chosen = choose_image(images, *info, rig.board->name());
  ASSERT_TRUE(chosen) << chosen.error().what();
  auto report = update_firmware(*rig.board, **chosen, UpdateOptions{});
  ASSERT_TRUE(report) << report.error().what();
  EXPECT_EQ(report->running_version, 0x01040000u);
  EXPECT_EQ(rig.sim->running_version(), 0x01040000u);
  EXPECT_NE(rig.sim->active_slot(), info->active_slot);
}

TEST(SimBoardLink, OpenSimLinkMakesABoardWithTheNodeOfItsAddress) {
  auto address = parse_board_address("sim:9");
  ASSERT_TRUE(address);
  auto link = open_sim_link(*address);
  ASSERT_TRUE(link) << link.error().what();
  Board board(std::move(*link));
  auto info = board.info();
  ASSERT_TRUE(info) << info.error().what();
  EXPECT_EQ(info->node_id, 9);
  EXPECT_EQ(board.name(), "sim:9");
}

}  // namespace
}  // namespace tetrapulse::host
