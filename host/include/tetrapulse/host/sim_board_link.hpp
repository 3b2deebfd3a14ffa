#pragma once
// SimLink to a simulated board of the virtual rig (firmware/boards/sim: the real firmware
// core on simulated hardware), reached through its USB bulk path with the real framing.
// Time is the board's simulated rig time: a conversation advances it, nothing waits.
#include <memory>

#include "tetrapulse/host/board_address.hpp"
#include "tetrapulse/host/sim_link.hpp"
#include "tetrapulse/sim_board/sim_board.hpp"

namespace tetrapulse::host {

// The SimBoardPort of one SimBoard (shared: a test may watch its LEDs and flash meanwhile).
std::shared_ptr<SimBoardPort> sim_board_port(std::shared_ptr<sim_board::SimBoard> board);

// A fresh simulated board, powered up with node id `address.node` and a serial number made
// from it, as a link named "sim:NODE". Each call makes a new board: its state lives as long
// as the link.
HostResult<std::unique_ptr<Link>> open_sim_link(const BoardAddress& address);

}  // namespace tetrapulse::host
