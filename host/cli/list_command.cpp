// `tetrapulse list`: the boards this host can reach: USB boards (application or
// bootloader), the CAN nodes that answer a broadcast GetInfo on each --can interface, and
// the boards on each --serial port given.
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "board_options.hpp"
#include "board_report.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "json_text.hpp"
#include "tetrapulse/host/can_link.hpp"
#include "tetrapulse/host/firmware_image.hpp"
#include "tetrapulse/host/serial_link.hpp"
#include "tetrapulse/host/usb_discovery.hpp"
#include "tetrapulse/host/usb_link.hpp"

namespace tetrapulse::cli {
namespace {

struct ListArgs {
  std::vector<std::string> can;
  std::vector<std::string> serial;
  bool no_usb = false;
  int timeout_ms = 300;
  bool json = false;
};

// One line of the list: a board with its Info, or something that is not (yet) one.
struct Row {
  std::string address;
  std::string mode;  // "application", "bootloader"
  std::optional<protocol::Info> info;
  std::string problem;
};

void list_usb(std::vector<Row>* rows, std::vector<std::string>* problems) {
  auto listed = host::list_usb_boards();
  if (!listed) {
    problems->push_back(listed.error().what());
    return;
  }
  for (const host::UsbBoardListing& l : *listed) {
    Row r{host::usb_link_name(l.serial), l.mode == protocol::UsbMode::kBootloader ? "bootloader" : "application", {}, l.problem};
    if (r.problem.empty() && l.mode == protocol::UsbMode::kApplication) {
      auto link = host::UsbLink::open(l.serial);
      if (!link) {
        r.problem = link.error().message;
      } else {
        host::Board board(std::move(*link));
        auto info = board.info();
        if (info) r.info = *info;
        else r.problem = info.error().message;
      }
    }
    if (!r.problem.empty()) r.problem = fmt::format("{} at USB {}: {}", r.address, l.port, r.problem);
    rows->push_back(r);
  }
}

void list_can(const std::string& iface, int timeout_ms, std::vector<Row>* rows, std::vector<std::string>* problems) {
  auto link = host::CanLink::open(iface, protocol::kCanBroadcastNode);
  if (!link) {
    problems->push_back(link.error().what());
    return;
  }
  if (auto sent = (*link)->send(protocol::Message{(*link)->take_seq(), protocol::GetInfo{}}); !sent) {
    problems->push_back(sent.error().what());
    return;
  }
  for (;;) {
    auto answer = (*link)->receive(std::chrono::milliseconds(timeout_ms));
    if (!answer) {
      if (answer.error().kind != host::HostErrorKind::kTimeout) problems->push_back(answer.error().what());
      break;
    }
    if (const auto* info = answer->message.get<protocol::Info>()) {
      rows->push_back(Row{fmt::format("can:{}:{}", iface, answer->source_node), "application", *info, ""});
    }
  }
}

void list_serial(const std::string& port, int timeout_ms, std::vector<Row>* rows, std::vector<std::string>* problems) {
  auto address = host::parse_serial_address(port);
  if (!address) {
    problems->push_back(address.error().what());
    return;
  }
  auto link = host::SerialLink::open(address->serial_path, address->baud);
  if (!link) {
    problems->push_back(link.error().what());
    return;
  }
  host::BoardTimeouts t;
  t.request = std::chrono::milliseconds(timeout_ms);
  host::Board board(std::move(*link), t);
  auto info = board.info();
  if (!info) {
    problems->push_back(info.error().what());
    return;
  }
  rows->push_back(Row{address->text(), "application", *info, ""});
}

int run_list(const ListArgs& a) {
  std::vector<Row> rows;
  std::vector<std::string> problems;
  if (!a.no_usb) list_usb(&rows, &problems);
  for (const std::string& iface : a.can) list_can(iface, a.timeout_ms, &rows, &problems);
  for (const std::string& port : a.serial) list_serial(port, a.timeout_ms, &rows, &problems);

  size_t boards = 0;
  std::string json;
  for (const Row& r : rows) {
    if (!r.problem.empty()) {
      problems.push_back(r.problem);
      continue;
    }
    ++boards;
    if (a.json) {
      JsonObject o;
      o.str("address", r.address).str("mode", r.mode);
      if (r.info) o.raw("info", info_json(r.address, *r.info));
      json += (json.empty() ? "" : ", ") + o.text();
    } else if (r.info) {
      fmt::print("{:<32} {} rev {}, firmware {}, node {}, serial {}\n", r.address, host::hw_model_name(r.info->hw_model),
                 r.info->hw_revision, version_text(r.info->fw_version), r.info->node_id, serial_text(*r.info));
    } else {
      fmt::print("{:<32} {} (DFU)\n", r.address, r.mode);
    }
  }
  if (a.json) {
    std::string skipped;
    for (const std::string& p : problems) skipped += (skipped.empty() ? "" : ", ") + json_string(p);
    fmt::print("{{\"boards\": [{}], \"problems\": [{}]}}\n", json, skipped);
  } else {
    for (const std::string& p : problems) std::fprintf(stderr, "tetrapulse list: %s\n", p.c_str());
    if (boards == 0) std::fprintf(stderr, "tetrapulse list: no board found\n");
  }
  return boards == 0 ? kExitNoDevice : kExitOk;
}

}  // namespace

void add_list_command(CLI::App& app, int* result) {
  auto a = std::make_shared<ListArgs>();
  auto* cmd = app.add_subcommand("list", "List the boards this host reaches: USB, CAN nodes, serial ports");
  cmd->add_option("--can", a->can, "Also ask every node on this SocketCAN interface (repeatable)");
  cmd->add_option("--serial", a->serial, "Also ask the board on this serial port, PATH[:BAUD] (repeatable)");
  cmd->add_flag("--no-usb", a->no_usb, "Do not look on USB");
  cmd->add_option("--timeout-ms", a->timeout_ms, "How long to wait for answers on CAN and serial")
      ->check(CLI::Range(1, 60000))
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "Machine-readable output (JSON)");
  cmd->footer("Exit code 4 when no board is found. Devices with the tetrapulse VID:PID that fail the checks\n"
              "(product string, PROTOCOL_INFO) are reported on stderr, not listed.");
  cmd->callback([a, result] { *result = run_list(*a); });
}

}  // namespace tetrapulse::cli
