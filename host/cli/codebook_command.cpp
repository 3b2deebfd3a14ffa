// `tetrapulse codebook`: choose LED codes for N targets and write the rig
// dataset's targets.yaml; `tetrapulse codebook check FILE`: say whether a
// file's codes meet the codebook constraints (protocol/SPEC.md §8), and which
// codes fail which constraint.
#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "tetrapulse/localizer/dataset_io.hpp"
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/protocol/codebook.hpp"
#include "tetrapulse/protocol/codebook_word.hpp"
#include "tetrapulse/protocol/codebook_workspace.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::cli {
namespace {

using protocol::CodebookFault;
using protocol::CodebookReport;
using protocol::CodebookSpec;
using protocol::CodeTiming;
using protocol::kNoRunLimit;

constexpr size_t kMarkers = protocol::kMarkersPerTarget;

constexpr const char* kDefaultsHelp =
    "Defaults by mode (any constraint option overrides them):\n"
    "  synchronized (default): --length 12, --distance 3 at equal phase, --weights 40%-60% of the\n"
    "      length rounded (5-7 for 12 bits), --max-zero-run 2 with on_off, none with two_level\n"
    "  --free-running: --length 15, --distance 3 under every cyclic shift (and from the code's own\n"
    "      shifts), --weights any, --max-zero-run 3 with on_off, none with two_level\n"
    "  both: --max-one-run none, --per marker, --seed 1, --bit-period-ns 10000000, ids 1..N,\n"
    "      geometry hardware/targets/paper-half-active.yaml (built in)\n"
    "Runs are cyclic: codes repeat. `check` takes the mode from the file's timebase and modulation.";

// Constraint options shared by generation and check; empty ones take the mode's default.
struct ConstraintArgs {
  std::optional<int> length;
  std::optional<int> distance;
  std::string weights;       // "A-B" or "any"
  std::string max_zero_run;  // "K" or "none"
  std::string max_one_run;   // "K" or "none"
  uint32_t iterations = CodebookSpec{}.search_iterations;
};

struct GenerateArgs {
  ConstraintArgs constraints;
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
  bool capacity = false;
};

struct CheckArgs {
  ConstraintArgs constraints;
  std::string file;
  std::string per = "auto";
};

// A command-line problem: one line, exit kExitUsage.
struct Usage {
  std::string message;
};

void add_constraint_options(CLI::App* cmd, ConstraintArgs* a) {
  cmd->add_option("--length", a->length, "Bits per code (1-64)")->check(CLI::Range(1, 64));
  cmd->add_option("--distance", a->distance, "Least number of bits in which any two codes differ")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--weights", a->weights, "Ones per code, A-B (e.g. 5-7), or 'any'");
  cmd->add_option("--max-zero-run", a->max_zero_run, "Longest cyclic run of 0 bits (LED dark), or 'none'");
  cmd->add_option("--max-one-run", a->max_one_run, "Longest cyclic run of 1 bits, or 'none'");
}

std::optional<int> parse_int(const std::string& text) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (text.empty() || text.size() > 6 || !std::all_of(text.begin(), text.end(), digit)) return std::nullopt;
  return std::stoi(text);
}

tl::expected<uint8_t, Usage> parse_run(const std::string& option, const std::string& text, uint8_t fallback,
                                       int length) {
  if (text.empty()) return fallback;
  if (text == "none") return kNoRunLimit;
  const std::optional<int> k = parse_int(text);
  if (!k || *k > length) {
    return tl::unexpected(Usage{fmt::format("{}: '{}' is not 'none' or a number from 0 to {}", option, text, length)});
  }
  return static_cast<uint8_t>(*k);
}

protocol::ZeroBit zero_bit(ModulationKind modulation) {
  return modulation == ModulationKind::kOnOff ? protocol::ZeroBit::kDark : protocol::ZeroBit::kDim;
}

// The spec for a mode: the recommended one (SPEC.md §8.4), then the options given.
tl::expected<CodebookSpec, Usage> make_spec(const ConstraintArgs& a, CodeTiming timing, ModulationKind modulation,
                                            std::optional<int> file_length) {
  const int given_length = a.length ? *a.length : file_length ? *file_length : 0;
  CodebookSpec s = protocol::recommended_spec(timing, zero_bit(modulation), static_cast<uint8_t>(given_length));
  const int L = s.length;
  if (a.distance) {
    if (*a.distance > L) {
      return tl::unexpected(Usage{fmt::format("--distance: {} exceeds the code length {}", *a.distance, L)});
    }
    s.min_distance = static_cast<uint8_t>(*a.distance);
  }
  if (a.weights == "any") {
    s.min_weight = 0;
    s.max_weight = static_cast<uint8_t>(L);
  } else if (!a.weights.empty()) {
    const size_t dash = a.weights.find('-');
    const std::optional<int> lo = dash == std::string::npos ? std::nullopt : parse_int(a.weights.substr(0, dash));
    const std::optional<int> hi = dash == std::string::npos ? std::nullopt : parse_int(a.weights.substr(dash + 1));
    if (!lo || !hi || *lo > *hi || *hi > L) {
      return tl::unexpected(
          Usage{fmt::format("--weights: '{}' is not 'any' or A-B with 0 <= A <= B <= {}", a.weights, L)});
    }
    s.min_weight = static_cast<uint8_t>(*lo);
    s.max_weight = static_cast<uint8_t>(*hi);
  }
  auto zeros = parse_run("--max-zero-run", a.max_zero_run, s.max_zero_run, L);
  if (!zeros) return tl::unexpected(zeros.error());
  auto ones = parse_run("--max-one-run", a.max_one_run, s.max_one_run, L);
  if (!ones) return tl::unexpected(ones.error());
  s.max_zero_run = *zeros;
  s.max_one_run = *ones;
  s.search_iterations = a.iterations;
  return s;
}

std::string describe(const CodebookSpec& s) {
  std::string out = fmt::format("{}, {} bits, distance >= {}{}",
                                s.timing == CodeTiming::kFreeRunning ? "free-running" : "synchronized", s.length,
                                s.min_distance, s.timing == CodeTiming::kFreeRunning ? " under every shift" : "");
  if (s.min_weight > 0 || s.max_weight < s.length) out += fmt::format(", weights {}-{}", s.min_weight, s.max_weight);
  if (s.max_zero_run < s.length) out += fmt::format(", zero runs <= {}", s.max_zero_run);
  if (s.max_one_run < s.length) out += fmt::format(", one runs <= {}", s.max_one_run);
  return out;
}

std::string code_text(uint64_t w, uint32_t length) {
  std::string s(length, '0');
  for (uint32_t i = 0; i < length; ++i) s[i] = ((w >> i) & 1u) ? '1' : '0';
  return s;
}

// Runs the search for spec.count codes; the codes found (fewer when it fell short).
std::vector<uint64_t> search_codes(const CodebookSpec& spec, protocol::CodebookWorkspace& ws) {
  std::vector<uint64_t> codes(spec.count);
  const protocol::Result<size_t> n = protocol::generate(spec, codes.data(), codes.size(), ws);
  codes.resize(n.ok() ? *n : 0);
  return codes;
}

// Which single relaxation of the spec reaches the count: one hint per constraint.
std::string relaxation_hints(const CodebookSpec& spec, const ConstraintArgs& given, ModulationKind modulation,
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
  const std::array<Eigen::Vector3d, 4> p = {Eigen::Vector3d(0.0, -0.08255, 0.1183),
                                            Eigen::Vector3d(0.0, 0.0652, 0.09225),
                                            Eigen::Vector3d(0.0313, -0.01105, 0.02695),
                                            Eigen::Vector3d(-0.0401, 0.01245, 0.03105)};
  for (size_t k = 0; k < kMarkers; ++k) t.markers[k].position_m = p[k];
  return t;
}

void fail_line(const std::string& message) { fmt::print(stderr, "tetrapulse codebook: {}\n", message); }

int run_generate(const GenerateArgs& a) {
  if (!a.capacity && (!a.targets || a.out.empty())) {
    fail_line("--targets and --out are required (or `tetrapulse codebook check FILE`, or --capacity)");
    return kExitUsage;
  }
  const ModulationKind modulation = a.modulation == "two_level" ? ModulationKind::kTwoLevel : ModulationKind::kOnOff;
  if (a.low && modulation != ModulationKind::kTwoLevel) {
    fail_line("--low: only meaningful with --modulation two_level");
    return kExitUsage;
  }
  const CodeTiming timing = a.free_running ? CodeTiming::kFreeRunning : CodeTiming::kSynchronized;
  auto spec = make_spec(a.constraints, timing, modulation, std::nullopt);
  if (!spec) {
    fail_line(spec.error().message);
    return kExitUsage;
  }
  spec->seed = a.seed;
  const auto ws = std::make_unique<protocol::CodebookWorkspace>();

  if (a.capacity) {
    std::vector<uint64_t> codes(protocol::CodebookWorkspace::kMaxCandidates);
    const protocol::Result<size_t> n = protocol::find_largest(*spec, codes.data(), codes.size(), *ws);
    if (!n.ok()) {
      fail_line(fmt::format("{}: {}", describe(*spec), protocol::check_spec(*spec).detail));
      return kExitUsage;
    }
    fmt::print("{}: the search found {} codes ({} targets with a code per marker, {} with a code per target); "
               "more may exist\n",
               describe(*spec), *n, *n / kMarkers, *n);
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
      fail_line(file.error().what());
      return kExitBadInput;
    }
    shapes = file->targets;
    if (shapes.size() != 1 && shapes.size() != targets) {
      fail_line(fmt::format("--geometry {}: has {} targets; --targets {} needs 1 or {}", a.geometry, shapes.size(),
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
    fail_line(fmt::format("--ids: need {} distinct non-negative ids, got '{}'", targets, fmt::join(ids, ",")));
    return kExitUsage;
  }

  const std::vector<uint64_t> codes = search_codes(*spec, *ws);
  if (codes.size() < spec->count) {
    fail_line(fmt::format("found only {} of the {} codes that {} targets need ({}); {}", codes.size(), spec->count,
                          targets, describe(*spec),
                          relaxation_hints(*spec, a.constraints, modulation, per_marker, targets, codes.size(), *ws)));
    return kExitCheckFailed;
  }

  TargetsFile out;
  out.timebase.synchronized = timing == CodeTiming::kSynchronized;
  out.timebase.epoch_ns = 0;
  out.timebase.bit_period_ns = a.bit_period_ns;
  out.modulation.kind = modulation;
  out.modulation.low = modulation == ModulationKind::kTwoLevel ? a.low.value_or(0.3) : 0.0;
  for (size_t i = 0; i < targets; ++i) {
    Target t = shapes.size() == targets ? shapes[i] : shapes[0];
    t.id = ids[i];
    if (shapes.size() != targets) t.name = fmt::format("{}-{}", t.name.empty() ? "target" : t.name, t.id);
    for (size_t k = 0; k < kMarkers; ++k) {
      const uint64_t w = codes[per_marker ? kMarkers * i + k : i];
      t.markers[k].code = Code{w, spec->length};
    }
    out.targets.push_back(std::move(t));
  }
  // Per-board configuration (the code table a board plays) belongs here once
  // the protocol's configuration messages exist; targets.yaml is the source.
  auto written = write_text_file(a.out, format_targets_yaml(out));
  if (!written) {
    fail_line(written.error().what());
    return kExitBadInput;
  }
  fmt::print("{}: {} targets, {} codes ({}), seed {}\n", a.out, targets, codes.size(), describe(*spec), a.seed);
  return kExitOk;
}

// ---- check ----

std::string fault_text(const CodebookReport& r, const CodebookSpec& spec, const std::vector<std::string>& labels,
                       const std::vector<uint64_t>& codes) {
  const std::string who = fmt::format("{} '{}'", labels[r.code], code_text(codes[r.code], spec.length));
  switch (r.fault) {
    case CodebookFault::kWeightTooLow:
      return fmt::format("{}: {} ones, fewer than {} (--weights)", who, r.value, r.limit);
    case CodebookFault::kWeightTooHigh:
      return fmt::format("{}: {} ones, more than {} (--weights)", who, r.value, r.limit);
    case CodebookFault::kZeroRunTooLong:
      return fmt::format("{}: {} zeros in a row (cyclically), more than {} (--max-zero-run)", who, r.value, r.limit);
    case CodebookFault::kOneRunTooLong:
      return fmt::format("{}: {} ones in a row (cyclically), more than {} (--max-one-run)", who, r.value, r.limit);
    case CodebookFault::kPhaseAmbiguous:
      return fmt::format("{}: shifted by {} bits it differs from itself in only {} bits, fewer than {}; a "
                         "free-running reader cannot tell its phase (--distance)",
                         who, r.shift, r.value, r.limit);
    case CodebookFault::kTooClose: {
      const std::string other = fmt::format("{} '{}'", labels[r.other], code_text(codes[r.other], spec.length));
      if (spec.timing == CodeTiming::kFreeRunning) {
        return fmt::format("{} and {} are at distance {} under shift {}, fewer than {} (--distance)", who, other,
                           r.value, r.shift, r.limit);
      }
      return fmt::format("{} and {} differ in only {} bits, fewer than {} (--distance)", who, other, r.value, r.limit);
    }
    case CodebookFault::kBitsBeyondLength:
      return fmt::format("{}: longer than {} bits", who, spec.length);
    case CodebookFault::kBadSpec:
    case CodebookFault::kNone:
      break;
  }
  return fmt::format("{}: {}", who, protocol::codebook_fault_name(r.fault));
}

int run_check(const CheckArgs& a) {
  auto file = read_targets_yaml(a.file);
  if (!file) {
    fail_line(file.error().what());
    return kExitBadInput;
  }
  if (file->modulation.kind == ModulationKind::kConstant) {
    fail_line(fmt::format("{}: modulation.kind is constant, so its LEDs play no codes", a.file));
    return kExitCheckFailed;
  }
  // Every marker needs a code of one common length (frequency codes, which may
  // differ in length, are a later codebook family).
  std::vector<std::string> problems;
  std::optional<int> length;
  for (size_t i = 0; i < file->targets.size(); ++i) {
    for (size_t k = 0; k < kMarkers; ++k) {
      const auto& code = file->targets[i].markers[k].code;
      const std::string where = fmt::format("targets[{}] (id {}) marker {}", i, file->targets[i].id, k);
      if (!code) {
        problems.push_back(where + ": no code (it would emit constantly and cannot be identified)");
      } else if (!length) {
        length = static_cast<int>(code->length);
      } else if (static_cast<int>(code->length) != *length) {
        problems.push_back(fmt::format("{}: {} bits, but other codes have {}", where, code->length, *length));
      }
    }
  }
  if (!problems.empty()) {
    for (const std::string& p : problems) fail_line(fmt::format("{}: {}", a.file, p));
    return kExitCheckFailed;
  }
  const bool same_within_targets = std::all_of(file->targets.begin(), file->targets.end(), [](const Target& t) {
    return std::all_of(t.markers.begin(), t.markers.end(), [&](const Marker& m) { return *m.code == *t.markers[0].code; });
  });
  const bool per_target = a.per == "target" || (a.per == "auto" && same_within_targets);
  if (per_target && !same_within_targets) {
    fail_line(fmt::format("{}: --per target, but some target's markers play different codes", a.file));
    return kExitCheckFailed;
  }

  const CodeTiming timing = file->timebase.synchronized ? CodeTiming::kSynchronized : CodeTiming::kFreeRunning;
  auto spec = make_spec(a.constraints, timing, file->modulation.kind, length);
  if (!spec) {
    fail_line(spec.error().message);
    return kExitUsage;
  }
  if (a.constraints.length && *a.constraints.length != *length) {
    fail_line(fmt::format("{}: codes have {} bits, not {} (--length)", a.file, *length, *a.constraints.length));
    return kExitCheckFailed;
  }

  std::vector<uint64_t> codes;
  std::vector<std::string> labels;
  for (size_t i = 0; i < file->targets.size(); ++i) {
    const Target& t = file->targets[i];
    for (size_t k = 0; k < (per_target ? 1 : kMarkers); ++k) {
      codes.push_back(t.markers[k].code->bits);
      labels.push_back(per_target ? fmt::format("targets[{}] (id {})", i, t.id)
                                  : fmt::format("targets[{}] (id {}) marker {}", i, t.id, k));
    }
  }
  if (codes.size() > 0xFFFF) {
    fail_line(fmt::format("{}: more than 65535 codes", a.file));
    return kExitCheckFailed;
  }

  constexpr size_t kShown = 20;
  size_t faults = 0;
  uint32_t closest = spec->length + 1;
  auto note = [&](const CodebookReport& r) {
    if (r.ok()) return;
    if (faults++ < kShown) fail_line(fmt::format("{}: {}", a.file, fault_text(r, *spec, labels, codes)));
  };
  for (size_t i = 0; i < codes.size(); ++i) note(protocol::check_code(*spec, codes[i], static_cast<uint16_t>(i)));
  for (size_t i = 0; i < codes.size(); ++i) {
    for (size_t j = i + 1; j < codes.size(); ++j) {
      const CodebookReport r = protocol::check_pair(*spec, codes[i], static_cast<uint16_t>(i), codes[j],
                                                    static_cast<uint16_t>(j));
      note(r);
      const uint32_t d = timing == CodeTiming::kFreeRunning
                             ? protocol::cyclic_distance(codes[i], codes[j], spec->length).distance
                             : protocol::hamming_distance(codes[i], codes[j]);
      closest = std::min(closest, d);
    }
  }
  const std::string what = fmt::format("{} codes (one per {})", codes.size(), per_target ? "target" : "marker");
  if (faults > 0) {
    if (faults > kShown) fail_line(fmt::format("{}: ... and {} more", a.file, faults - kShown));
    fail_line(fmt::format("{}: {} of {} fail: {}", a.file, faults, what, describe(*spec)));
    return kExitCheckFailed;
  }
  fmt::print("{}: {} pass: {}{}\n", a.file, what, describe(*spec),
             codes.size() > 1 ? fmt::format("; closest pair at distance {}", closest) : std::string());
  return kExitOk;
}

}  // namespace

void add_codebook_command(CLI::App& app, int* result) {
  auto* cmd = app.add_subcommand("codebook", "Choose LED codes for N targets and write targets.yaml");
  cmd->footer(kDefaultsHelp);
  auto gen = std::make_shared<GenerateArgs>();
  cmd->add_option("--targets", gen->targets, "Number of targets (1-1024)")->check(CLI::Range(1, 1024));
  cmd->add_option("--per", gen->per, "One code per marker (4 per target) or one per target (geometry names markers)")
      ->check(CLI::IsMember({"marker", "target"}))
      ->capture_default_str();
  cmd->add_flag("--free-running", gen->free_running,
                "Boards run free (timebase.synchronized: false): codes must differ under every cyclic shift");
  add_constraint_options(cmd, &gen->constraints);
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

  auto* check = cmd->add_subcommand("check", "Check the codes of a targets.yaml against the codebook constraints");
  check->footer(kDefaultsHelp);
  auto chk = std::make_shared<CheckArgs>();
  check->add_option("file", chk->file, "targets.yaml to check")->required();
  check->add_option("--per", chk->per, "marker, target, or auto (target when each target's markers share a code)")
      ->check(CLI::IsMember({"auto", "marker", "target"}))
      ->capture_default_str();
  add_constraint_options(check, &chk->constraints);

  cmd->require_subcommand(0, 1);
  check->callback([result, chk] { *result = run_check(*chk); });
  cmd->callback([result, gen, check] {
    if (check->parsed()) return;
    *result = run_generate(*gen);
  });
}

}  // namespace tetrapulse::cli
