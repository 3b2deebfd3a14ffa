// `tetrapulse config`: show a board's running configuration, or set it from a board
// configuration file (`--file`, as `tetrapulse codebook` writes them) and/or from options,
// read it back to check, and optionally store it (`--persist`). `--pwm-hz` plays a raw PWM
// on all four markers for bench checks, as the square-wave code protocol::pwm_code gives.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "board_options.hpp"
#include "board_report.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "json_text.hpp"
#include "tetrapulse/host/board_config_yaml.hpp"
#include "tetrapulse/host/config_text.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"
#include "tetrapulse/protocol/pwm_code.hpp"

namespace tetrapulse::cli {
namespace {

using host::HostErrorKind;

struct ConfigArgs {
  BoardOptions board;
  std::string file;
  bool persist = false;
  bool factory_reset = false;
  std::optional<int64_t> node_id, target_id, low_level, bit_period_ns, epoch_ns, brightness, current_limit_ma,
      gpio_edge_period_ns, gpio_edge_epoch_ns;
  std::vector<std::string> codes;  // "I=BITS"
  std::optional<std::string> modulation, sync_source, gpio_edge, gpio_edge_numbering;
  std::optional<double> pwm_hz;
  double duty = 0.5;

  bool sets_fields() const {
    return pwm_hz || node_id || target_id || low_level || bit_period_ns || epoch_ns || brightness || current_limit_ma ||
           gpio_edge_period_ns || gpio_edge_epoch_ns || !codes.empty() || modulation || sync_source || gpio_edge ||
           gpio_edge_numbering;
  }
};

std::vector<uint8_t> bytes_of(const protocol::Config& c) {
  std::vector<uint8_t> out(protocol::kConfigSize);
  protocol::ByteWriter w(out.data(), out.size());
  protocol::encode_config(c, w);
  return out;
}

tl::unexpected<host::HostError> bad_option(const std::string& what) {
  return host::host_error(HostErrorKind::kBadInput, "", what);
}

// The highest PWM a board plays: two bits (one on, one off) of its shortest bit period.
constexpr double kMaxPwmHz = 1e9 / (2.0 * protocol::kMinBitPeriodNs);
constexpr double kMinPwmHz = 0.01;  // protocol::pwm_code's floor

// --pwm-hz and --duty as the code and bit period a board plays; an error names the option and its bound.
host::HostResult<protocol::PwmCode> pwm_of(double hz, double duty) {
  if (!std::isfinite(hz) || hz < kMinPwmHz || hz > kMaxPwmHz) {
    return bad_option(fmt::format(
        "--pwm-hz {:g}: outside {:g} Hz .. {:g} Hz (the highest is two bits of the shortest bit period, {} ns)", hz,
        kMinPwmHz, kMaxPwmHz, protocol::kMinBitPeriodNs));
  }
  if (!std::isfinite(duty) || duty <= 0 || duty >= 1) {
    return bad_option(fmt::format("--duty {:g}: must be between 0 and 1, both excluded", duty));
  }
  const auto mhz = static_cast<uint64_t>(std::llround(hz * 1000));
  const auto q16 = static_cast<uint32_t>(std::min(65535LL, std::max(1LL, std::llround(duty * 65536))));
  const protocol::Result<protocol::PwmCode> pwm = protocol::pwm_code(mhz, q16);
  if (!pwm.ok()) return bad_option(fmt::format("--pwm-hz {:g} --duty {:g}: no code plays it", hz, duty));
  return *pwm;
}

// The duty played exactly: lit bits over code bits (duty_q16 is its floor).
double pwm_duty(const protocol::PwmCode& p) { return double(protocol::word_weight(p.code.bits)) / p.code.length; }

// "1000 Hz duty 0.25 asked: plays 1000.000 Hz duty 0.2500 (...)": what the board will do, exactly.
std::string pwm_text(const ConfigArgs& a, const protocol::PwmCode& p) {
  return fmt::format(
      "PWM {:g} Hz duty {:g} asked: plays {:.3f} Hz duty {:.4f} ({} of {} bits lit on a {} ns bit period, duty "
      "steps of 1/{}) on all four markers",
      *a.pwm_hz, a.duty, p.frequency_millihertz / 1000.0, pwm_duty(p), protocol::word_weight(p.code.bits),
      p.code.length, p.bit_period_ns, p.code.length);
}

// The options on top of `c`; an error names the option.
host::HostResult<protocol::Config> apply_options(const ConfigArgs& a, const std::optional<protocol::PwmCode>& pwm,
                                                 protocol::Config c) {
  auto bad = [](const std::string& what) { return bad_option(what); };
  if (a.node_id) c.node_id = static_cast<uint8_t>(*a.node_id);
  if (a.target_id) c.target_id = static_cast<uint16_t>(*a.target_id);
  if (a.low_level) c.low_level = static_cast<uint16_t>(*a.low_level);
  if (a.bit_period_ns) c.bit_period_ns = static_cast<uint32_t>(*a.bit_period_ns);
  if (a.epoch_ns) c.epoch_ns = *a.epoch_ns;
  if (a.brightness) c.brightness = static_cast<uint16_t>(*a.brightness);
  if (a.current_limit_ma) c.current_limit_ma = static_cast<uint16_t>(*a.current_limit_ma);
  if (a.gpio_edge_period_ns) c.gpio_edge_period_ns = static_cast<uint32_t>(*a.gpio_edge_period_ns);
  if (a.gpio_edge_epoch_ns) c.gpio_edge_epoch_ns = *a.gpio_edge_epoch_ns;
  for (const std::string& spec : a.codes) {
    const size_t eq = spec.find('=');
    const std::string index = spec.substr(0, eq);
    if (eq == std::string::npos || index.size() != 1 || index[0] < '0' || index[0] > '3') {
      return bad(fmt::format("--code {}: expected MARKER=BITS with MARKER 0..3, e.g. 0=1101001110", spec));
    }
    std::string why;
    const auto code = host::parse_code(spec.substr(eq + 1), &why);
    if (!code) return bad(fmt::format("--code {}: '{}' {}", spec, spec.substr(eq + 1), why));
    c.codes[static_cast<size_t>(index[0] - '0')] = *code;
  }
  if (a.modulation) c.modulation = *host::parse_modulation(*a.modulation);
  if (a.sync_source) c.sync_source = *host::parse_sync_source(*a.sync_source);
  if (a.gpio_edge) c.gpio_edge = *host::parse_gpio_edge(*a.gpio_edge);
  if (a.gpio_edge_numbering) c.gpio_edge_numbering = *host::parse_gpio_edge_numbering(*a.gpio_edge_numbering);
  if (pwm) {
    if (!a.modulation) c.modulation = protocol::Modulation::kOnOff;
    if (c.modulation == protocol::Modulation::kConstant) {
      return bad("--pwm-hz: --modulation constant plays no code; use on_off or two_level");
    }
    c.codes.fill(pwm->code);
    c.bit_period_ns = pwm->bit_period_ns;
  }
  return c;
}

int show(host::Board& board, bool json) {
  auto config = board.config();
  if (!config) return report_failure("config", config.error());
  if (json) {
    fmt::print("{}\n", config_json(board.name(), *config));
  } else {
    fmt::print("{}", host::format_board_config_yaml(*config, "running configuration of " + board.name()));
  }
  return kExitOk;
}

int run_config(const ConfigArgs& a) {
  // Inputs first: a bad file or option fails before any board is touched.
  std::optional<protocol::PwmCode> pwm;
  if (a.pwm_hz) {
    auto p = pwm_of(*a.pwm_hz, a.duty);
    if (!p) return report_failure("config", p.error());
    pwm = *p;
  }
  std::optional<protocol::Config> from_file;
  if (!a.file.empty()) {
    auto c = host::read_board_config_yaml(a.file);
    if (!c) return report_failure("config", c.error());
    from_file = *c;
  }
  auto board = open_board(a.board);
  if (!board) return report_failure("config", board.error());
  host::Board& b = **board;
  if (a.factory_reset) {
    if (auto done = b.factory_reset(); !done) return report_failure("config", done.error());
  }
  if (!from_file && !a.sets_fields()) {
    if (a.persist) {
      if (auto done = b.persist(); !done) return report_failure("config", done.error());
    }
    return a.factory_reset && !a.persist ? kExitOk : show(b, a.board.json);
  }
  protocol::Config base;
  if (from_file) {
    base = *from_file;
  } else {
    auto running = b.config();
    if (!running) return report_failure("config", running.error());
    base = *running;
  }
  auto wanted = apply_options(a, pwm, base);
  if (!wanted) return report_failure("config", wanted.error());
  if (auto done = b.configure(*wanted); !done) return report_failure("config", done.error());
  // Read back, except when a CAN board was just moved to another node id.
  const bool moved = b.name().rfind("can:", 0) == 0 && wanted->node_id != base.node_id;
  if (!moved) {
    auto back = b.config();
    if (!back) return report_failure("config", back.error());
    if (bytes_of(*back) != bytes_of(*wanted)) {
      std::fprintf(stderr, "tetrapulse config: %s: the configuration read back differs from the one sent\n",
                   b.name().c_str());
      return kExitCheckFailed;
    }
  }
  if (a.persist) {
    if (auto done = b.persist(); !done) return report_failure("config", done.error());
  }
  if (a.board.json) {
    JsonObject out;
    out.str("address", b.name()).flag("configured", true).flag("verified", !moved).flag("persisted", a.persist);
    if (pwm) {
      out.raw("pwm", JsonObject()
                         .num("frequency_hz", pwm->frequency_millihertz / 1000.0)
                         .num("duty", pwm_duty(*pwm))
                         .str("code", host::code_text(pwm->code))
                         .num("bit_period_ns", pwm->bit_period_ns)
                         .text());
    }
    fmt::print("{}\n", out.raw("config", config_json(b.name(), *wanted)).text());
  } else {
    if (pwm) fmt::print("{}: {}\n", b.name(), pwm_text(a, *pwm));
    fmt::print("{}: configured{}{}\n", b.name(), moved ? fmt::format(" (now node {}: not read back)", wanted->node_id) : " and read back",
               a.persist ? ", persisted" : " (not persisted: --persist stores it)");
  }
  return kExitOk;
}

}  // namespace

void add_config_command(CLI::App& app, int* result) {
  auto a = std::make_shared<ConfigArgs>();
  auto* cmd = app.add_subcommand(
      "config", "Show a board's configuration, or set it from a board configuration file and/or options");
  add_board_options(cmd, &a->board);
  cmd->add_option("--file", a->file, "Board configuration YAML (as `tetrapulse codebook` writes) to apply")
      ->group("Configuration");
  cmd->add_flag("--persist", a->persist, "Store the configuration in the board's flash")->group("Configuration");
  cmd->add_flag("--factory-reset", a->factory_reset, "Go back to the factory configuration first")
      ->group("Configuration");
  const char* g = "Fields (SPEC.md 2.5; applied over --file, or over the running configuration)";
  cmd->add_option("--node-id", a->node_id, "CAN node id")->check(CLI::Range(1, 254))->group(g);
  cmd->add_option("--target-id", a->target_id, "Target (codebook) id")->check(CLI::Range(0, 65535))->group(g);
  auto* code = cmd->add_option("--code", a->codes, "MARKER=BITS, e.g. 0=1101001110 (BITS '' or - for no code); repeatable")
                   ->group(g);
  cmd->add_option("--modulation", a->modulation, "on_off, two_level or constant")
      ->check(CLI::IsMember({"on_off", "two_level", "constant"}))
      ->group(g);
  cmd->add_option("--low-level", a->low_level, "0-bit emission with two_level, x/65535")
      ->check(CLI::Range(0, 65535))
      ->group(g);
  auto* bit_period = cmd->add_option("--bit-period-ns", a->bit_period_ns, "Code bit period")
                         ->check(CLI::Range(int64_t{protocol::kMinBitPeriodNs}, int64_t{UINT32_MAX}))
                         ->group(g);
  cmd->add_option("--epoch-ns", a->epoch_ns, "Rig time at which bit 0 starts")->group(g);
  cmd->add_option("--brightness", a->brightness, "1-bit emission, x/65535")->check(CLI::Range(0, 65535))->group(g);
  cmd->add_option("--current-limit-ma", a->current_limit_ma, "LED current ceiling, 0 = hardware maximum")
      ->check(CLI::Range(0, 65535))
      ->group(g);
  cmd->add_option("--sync-source", a->sync_source, "none, gpio or can")
      ->check(CLI::IsMember({"none", "gpio", "can"}))
      ->group(g);
  cmd->add_option("--gpio-edge", a->gpio_edge, "Sync input edge: rising or falling")
      ->check(CLI::IsMember({"rising", "falling"}))
      ->group(g);
  cmd->add_option("--gpio-edge-period-ns", a->gpio_edge_period_ns, "Nominal interval between sync edges")
      ->check(CLI::Range(int64_t{protocol::kMinGpioEdgePeriodNs}, int64_t{UINT32_MAX}))
      ->group(g);
  cmd->add_option("--gpio-edge-epoch-ns", a->gpio_edge_epoch_ns, "Rig time of sync edge 0")->group(g);
  cmd->add_option("--gpio-edge-numbering", a->gpio_edge_numbering, "nearest_coarse_time or count_after_gap")
      ->check(CLI::IsMember({"nearest_coarse_time", "count_after_gap"}))
      ->group(g);
  const char* bench = "Bench PWM (a scope or a phone camera on the LEDs)";
  auto* pwm = cmd->add_option("--pwm-hz", a->pwm_hz,
                              "Play a plain PWM of F Hz (0.01 .. 50000) on all four markers: the square-wave code of "
                              "L <= 64 bits on bit period T >= 10 us (integer ns) that best gives --duty, then F. "
                              "Quantisation: duty in steps of 1/L (1/64 up to 1562 Hz, coarser above, 1/2 at "
                              "50 kHz); period L T within L/2 ns of 1/F; a free-running board's crystal (<= 200 ppm) "
                              "adds its error to F. Prints what is played exactly. Sets --modulation on_off unless "
                              "given; replaces --code and --bit-period-ns")
                  ->group(bench);
  pwm->excludes(code)->excludes(bit_period);
  cmd->add_option("--duty", a->duty, "Fraction of each PWM period lit, strictly between 0 and 1")
      ->needs(pwm)
      ->capture_default_str()
      ->group(bench);
  cmd->callback([a, result] { *result = run_config(*a); });
}

}  // namespace tetrapulse::cli
