// `tetrapulse codebook`: choose LED codes for N targets (protocol/SPEC.md §8)
// and write the rig dataset's targets.yaml.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "codebook_constraints.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "frequency_codebook_command.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/host/board_config_yaml.hpp"
#include "tetrapulse/host/config_text.hpp"
#include "tetrapulse/host/target_board_config.hpp"
#include "tetrapulse/protocol/can_id.hpp"
#include "tetrapulse/codebook/codebook.hpp"
#include "tetrapulse/codebook/codebook_workspace.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::cli {
namespace {

using protocol::CodebookSpec;
using protocol::CodeTiming;

constexpr size_t kMarkers = protocol::kMarkersPerTarget;

struct GenerateArgs {
  CodebookConstraintArgs constraints;
  std::optional<int> targets;
  std::string per = "marker";
  bool free_running = false;
  std::string modulation = "on_off";
  std::optional<double> low;
  int64_t bit_period_ns = 10'000'000;
  uint64_t seed = 1;
  std::string geometry;
  std::vector<int> ids;
  std::string out;
  std::optional<std::string> board_configs;  // folder; default: "boards" beside --out
  std::optional<std::string> board_sync;     // none | gpio | can
  bool capacity = false;
  FrequencyCodebookArgs frequency;
};

std::vector<uint64_t> search_codes(const CodebookSpec& spec, protocol::CodebookWorkspace& ws) {
  std::vector<uint64_t> codes(spec.count);
  const protocol::Result<size_t> n = protocol::generate(spec, codes.data(), codes.size(), ws);
  codes.resize(n.ok() ? *n : 0);
  return codes;
}

// Which single relaxation of the spec reaches the count: one hint per constraint.
std::string relaxation_hints(const CodebookSpec& spec, const CodebookConstraintArgs& given, ModulationKind modulation,
                             bool per_marker, size_t targets, size_t found, protocol::CodebookWorkspace& ws) {
  std::vector<std::string> hints;
  auto reaches = [&](CodebookSpec s) { return search_codes(s, ws).size() >= s.count; };
  for (int extra = 1; extra <= 12 && spec.length + extra <= 64; ++extra) {
    CodebookSpec s = spec;
    s.length = static_cast<uint8_t>(spec.length + extra);
    if (given.weights.empty()) {  // the recommended weights grow with the length
      const CodebookSpec r = protocol::recommended_spec(spec.timing, zero_bit(modulation), s.length);
      s.min_weight = r.min_weight;
      s.max_weight = r.max_weight;
    } else if (s.max_weight == spec.length) {
      s.max_weight = s.length;
    }
    if (reaches(s)) {
      hints.push_back(fmt::format("--length {}", int(s.length)));
      break;
    }
  }
  if (spec.min_weight > 0 || spec.max_weight < spec.length) {
    CodebookSpec s = spec;
    s.min_weight = static_cast<uint8_t>(spec.min_weight > 0 ? spec.min_weight - 1 : 0);
    s.max_weight = static_cast<uint8_t>(std::min<int>(spec.max_weight + 1, spec.length));
    if (reaches(s)) hints.push_back(fmt::format("--weights {}-{}", int(s.min_weight), int(s.max_weight)));
  }
  if (spec.max_zero_run < spec.length) {
    CodebookSpec s = spec;
    ++s.max_zero_run;
    if (reaches(s)) hints.push_back(fmt::format("--max-zero-run {}", int(s.max_zero_run)));
  }
  if (spec.max_one_run < spec.length) {
    CodebookSpec s = spec;
    ++s.max_one_run;
    if (reaches(s)) hints.push_back(fmt::format("--max-one-run {}", int(s.max_one_run)));
  }
  if (spec.min_distance > 1) {
    CodebookSpec s = spec;
    --s.min_distance;
    if (reaches(s)) hints.push_back(fmt::format("--distance {} (tolerates fewer misread bits)", int(s.min_distance)));
  }
  if (per_marker) {
    CodebookSpec s = spec;
    s.count = static_cast<uint16_t>(targets);
    if (reaches(s)) hints.push_back(fmt::format("--per target ({} codes)", targets));
  }
  const size_t fit = per_marker ? found / kMarkers : found;
  const std::string fewer = fit > 0 ? fmt::format("--targets {}", fit) : std::string("other constraints");
  if (hints.empty()) return fmt::format("no single relaxation is enough: relax several, or use {}", fewer);
  std::string out = "any one of these is enough: ";
  for (const std::string& h : hints) out += h + ", ";
  return out + "or " + fewer;
}

// The paper's half-size active target (hardware/targets/paper-half-active.yaml).
Target builtin_geometry() {
  Target t;
  t.name = "paper-half-active";
  t.marker_diameter_m = 0.01;
  const std::array<Eigen::Vector3d, 4> p = {
      Eigen::Vector3d(0.0, -0.08255, 0.1183), Eigen::Vector3d(0.0, 0.0652, 0.09225),
      Eigen::Vector3d(0.0313, -0.01105, 0.02695), Eigen::Vector3d(-0.0401, 0.01245, 0.03105)};
  for (size_t k = 0; k < kMarkers; ++k) t.markers[k].position_m = p[k];
  return t;
}

int write_board_configs(const TargetsFile& file, const std::string& folder, protocol::SyncSource sync) {
  for (const Target& t : file.targets) {
    if (t.id > 65535) {
      codebook_error(fmt::format("target id {}: a board's target_id is 0..65535", t.id));
      return kExitUsage;
    }
  }
  if (file.timebase.bit_period_ns < protocol::kMinBitPeriodNs || file.timebase.bit_period_ns > UINT32_MAX) {
    codebook_error(fmt::format("--bit-period-ns {}: a board plays {}..{} ns", file.timebase.bit_period_ns,
                               protocol::kMinBitPeriodNs, UINT32_MAX));
    return kExitUsage;
  }
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  for (size_t i = 0; i < file.targets.size(); ++i) {
    const Target& t = file.targets[i];
    const std::string path = (std::filesystem::path(folder) / fmt::format("target-{}.yaml", t.id)).string();
    const std::string header = fmt::format(
        "Board configuration for target {}{} (tetrapulse codebook); apply with\n"
        "tetrapulse config --file {} --persist --usb SERIAL (or --can IFACE:NODE, --serial PORT)",
        t.id, t.name.empty() ? "" : " (" + t.name + ")", path);
    auto written = write_text_file(path, host::format_board_config_yaml(host::target_board_config(file, i, sync), header));
    if (!written) {
      codebook_error(written.error().what());
      return kExitBadInput;
    }
  }
  if (file.targets.size() > protocol::kCanLastBoardNode) {
    std::fprintf(stderr, "tetrapulse codebook: more than %u targets: CAN node ids repeat, give each bus its own\n",
                 unsigned{protocol::kCanLastBoardNode});
  }
  return kExitOk;
}

int run_generate(const GenerateArgs& a) {
  if (!a.capacity && (!a.targets || a.out.empty())) {
    codebook_error("--targets and --out are required (or `tetrapulse codebook check FILE`, or --capacity)");
    return kExitUsage;
  }
  const ModulationKind modulation = a.modulation == "two_level" ? ModulationKind::kTwoLevel : ModulationKind::kOnOff;
  if (a.low && modulation != ModulationKind::kTwoLevel) {
    codebook_error("--low: only meaningful with --modulation two_level");
    return kExitUsage;
  }
  if (a.frequency.frequency() && a.capacity) return run_frequency_capacity(a.frequency, modulation);
  const CodeTiming timing = a.free_running ? CodeTiming::kFreeRunning : CodeTiming::kSynchronized;
  auto spec = codebook_spec(a.constraints, timing, modulation, std::nullopt);
  if (!spec) {
    codebook_error(spec.error().message);
    return kExitUsage;
  }
  spec->seed = a.seed;
  const auto ws = std::make_unique<protocol::CodebookWorkspace>();

  if (a.capacity) {
    std::vector<uint64_t> codes(protocol::CodebookWorkspace::kMaxCandidates);
    protocol::CodebookSearchStats stats;
    const protocol::Result<size_t> n = protocol::find_largest(*spec, codes.data(), codes.size(), *ws, &stats);
    if (!n.ok()) {
      codebook_error(fmt::format("{}: {}", describe_codebook_spec(*spec), protocol::check_spec(*spec).detail));
      return kExitUsage;
    }
    fmt::print(
        "{}: the search found {} codes ({} targets with a code per marker, {} with a code per target); {}\n",
        describe_codebook_spec(*spec), *n, *n / kMarkers, *n,
        stats.proven_maximum ? "no larger set exists" : "more may exist");
    return kExitOk;
  }

  const size_t targets = static_cast<size_t>(*a.targets);
  const bool per_marker = a.per == "marker";
  spec->count = static_cast<uint16_t>(per_marker ? kMarkers * targets : targets);

  // Geometry: one target for all, or one per target in order.
  std::vector<Target> shapes{builtin_geometry()};
  if (!a.geometry.empty()) {
    auto file = read_targets_yaml(a.geometry);
    if (!file) {
      codebook_error(file.error().what());
      return kExitBadInput;
    }
    shapes = file->targets;
    if (shapes.size() != 1 && shapes.size() != targets) {
      codebook_error(fmt::format("--geometry {}: has {} targets; --targets {} needs 1 or {}", a.geometry, shapes.size(),
                                 targets, targets));
      return kExitUsage;
    }
  }
  std::vector<int> ids = a.ids;
  if (ids.empty()) {
    for (size_t i = 0; i < targets; ++i) ids.push_back(shapes.size() == targets ? shapes[i].id : int(i) + 1);
  }
  if (ids.size() != targets || std::set<int>(ids.begin(), ids.end()).size() != targets ||
      *std::min_element(ids.begin(), ids.end()) < 0) {
    codebook_error(fmt::format("--ids: need {} distinct non-negative ids, got '{}'", targets, fmt::join(ids, ",")));
    return kExitUsage;
  }

  // Frequency codes come from the camera's sampling, not from the search.
  std::optional<FrequencyChoice> frequency;
  if (a.frequency.frequency()) {
    auto chosen = choose_frequency_codebook(a.frequency, modulation, spec->count, per_marker, targets);
    if (!chosen) {
      codebook_error(chosen.error().message);
      return chosen.error().exit;
    }
    frequency = std::move(*chosen);
  }
  const std::vector<uint64_t> codes = frequency ? frequency->words() : search_codes(*spec, *ws);
  if (codes.size() < spec->count) {
    codebook_error(
        fmt::format("found only {} of the {} codes that {} targets need ({}); {}", codes.size(), spec->count, targets,
                    describe_codebook_spec(*spec),
                    relaxation_hints(*spec, a.constraints, modulation, per_marker, targets, codes.size(), *ws)));
    return kExitCheckFailed;
  }

  TargetsFile out;
  out.timebase.synchronized = timing == CodeTiming::kSynchronized;
  out.timebase.epoch_ns = 0;
  out.timebase.bit_period_ns = frequency ? frequency->bit_period_ns : a.bit_period_ns;
  out.modulation.kind = modulation;
  out.modulation.low = modulation == ModulationKind::kTwoLevel ? a.low.value_or(0.3) : 0.0;
  for (size_t i = 0; i < targets; ++i) {
    Target t = shapes.size() == targets ? shapes[i] : shapes[0];
    t.id = ids[i];
    if (shapes.size() != targets) t.name = fmt::format("{}-{}", t.name.empty() ? "target" : t.name, t.id);
    for (size_t k = 0; k < kMarkers; ++k) {
      const size_t j = per_marker ? kMarkers * i + k : i;
      t.markers[k].code = frequency ? frequency->codes[j] : Code{spec->length, codes[j]};
    }
    out.targets.push_back(std::move(t));
  }
  auto written = write_text_file(a.out, format_targets_yaml(out));
  if (!written) {
    codebook_error(written.error().what());
    return kExitBadInput;
  }
  // One board configuration per target, for `tetrapulse config --file`.
  const std::string folder =
      a.board_configs.value_or((std::filesystem::path(a.out).parent_path() / "boards").string());
  const protocol::SyncSource sync = *host::parse_sync_source(a.board_sync.value_or(timing == CodeTiming::kSynchronized ? "can" : "none"));
  if (const int r = write_board_configs(out, folder, sync); r != kExitOk) return r;
  fmt::print("{}: {} targets, {} codes ({}), seed {}; board configurations in {}/ (sync {})\n", a.out, targets,
             codes.size(), frequency ? frequency->description : describe_codebook_spec(*spec), a.seed, folder, host::sync_source_name(sync));
  return kExitOk;
}

}  // namespace

void add_codebook_command(CLI::App& app, int* result) {
  auto* cmd = app.add_subcommand("codebook", "Choose LED codes for N targets and write targets.yaml");
  cmd->footer(kCodebookDefaultsHelp);
  auto gen = std::make_shared<GenerateArgs>();
  cmd->add_option("--targets", gen->targets, "Number of targets (1-1024)")->check(CLI::Range(1, 1024));
  cmd->add_option("--per", gen->per, "One code per marker (4 per target) or one per target (geometry names markers)")
      ->check(CLI::IsMember({"marker", "target"}))
      ->capture_default_str();
  cmd->add_flag("--free-running", gen->free_running,
                "Boards run free (timebase.synchronized: false): codes must differ under every cyclic shift");
  add_codebook_constraint_options(cmd, &gen->constraints);
  cmd->add_option("--iterations", gen->constraints.iterations, "Search budget: local-search iterations")
      ->capture_default_str();
  cmd->add_option("--modulation", gen->modulation, "What a 0 bit does: on_off (dark) or two_level (dim)")
      ->check(CLI::IsMember({"on_off", "two_level"}))
      ->capture_default_str();
  cmd->add_option("--low", gen->low, "Relative emission of a 0 bit with two_level (default 0.3)")
      ->check(CLI::Range(0.0, 0.999));
  cmd->add_option("--bit-period-ns", gen->bit_period_ns, "Nominal bit period in ns")
      ->check(CLI::Range(int64_t{1}, int64_t{1'000'000'000'000}))
      ->capture_default_str();
  cmd->add_option("--seed", gen->seed, "Search seed: the same seed and options give the same codes")
      ->capture_default_str();
  cmd->add_option("--geometry", gen->geometry,
                  "targets.yaml whose first target's markers serve every target (or its N targets in order)");
  cmd->add_option("--ids", gen->ids, "Target ids, comma-separated (default 1..N)")->delimiter(',');
  cmd->add_option("--out", gen->out, "targets.yaml to write");
  cmd->add_flag("--capacity", gen->capacity, "Only report how many codes the constraints allow (by search)");
  cmd->add_option("--board-configs", gen->board_configs,
                  "Folder for one board configuration per target, target-ID.yaml (default: boards/ beside --out)");
  cmd->add_option("--board-sync", gen->board_sync,
                  "Sync source in the board configurations: none, gpio or can (default: can when synchronized, "
                  "none when free-running)")
      ->check(CLI::IsMember({"none", "gpio", "can"}));

  add_frequency_codebook_options(cmd, &gen->frequency);

  add_codebook_check_command(cmd, result);
  cmd->require_subcommand(0, 1);
  cmd->callback([result, gen, cmd] {
    if (cmd->got_subcommand("check")) return;
    if (cmd->count("--bit-period-ns") > 0) gen->frequency.bit_period_ns = gen->bit_period_ns;
    *result = run_generate(*gen);
  });
}

}  // namespace tetrapulse::cli
