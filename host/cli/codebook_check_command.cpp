// `tetrapulse codebook check FILE`: whether a targets.yaml's codes meet the
// codebook constraints (protocol/SPEC.md §8), and which codes fail which. Binary
// words by the binary rules (§8.4), square waves by the frequency rules at the
// camera given (§8.5), and in a mixed file each binary word apart from the square waves.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "codebook_constraints.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "frequency_codebook_check.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"
#include "tetrapulse/codebook/frequency_code.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::cli {
namespace {

using protocol::CodebookFault;
using protocol::CodebookReport;
using protocol::CodebookSpec;
using protocol::CodeTiming;

constexpr size_t kMarkers = protocol::kMarkersPerTarget;

struct CheckArgs {
  CodebookConstraintArgs constraints;
  FrequencyCodebookArgs frequency;  // the camera, for frequency codes
  std::string file;
  std::string per = "auto";
};

// One fault in the user's words: which codes, what was measured, which option bounds it.
std::string fault_text(const CodebookReport& r, const CodebookSpec& spec, const std::vector<std::string>& labels,
                       const std::vector<uint64_t>& codes) {
  const std::string who = fmt::format("{} '{}'", labels[r.code], code_text(Code{spec.length, codes[r.code]}));
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
      return fmt::format(
          "{}: shifted by {} bits it differs from itself in only {} bits, fewer than {}; a "
          "free-running reader cannot tell its phase (--distance)",
          who, r.shift, r.value, r.limit);
    case CodebookFault::kTooClose: {
      const std::string other = fmt::format("{} '{}'", labels[r.other], code_text(Code{spec.length, codes[r.other]}));
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

// The binary codes by the binary rules (SPEC.md §8.4): one common length, each code, each pair.
int check_binary_family(const CheckArgs& a, const TargetsFile& file, const std::vector<LabelledCode>& binary,
                        const std::string& what) {
  std::vector<std::string> problems;
  const uint32_t length = binary.front().code.length;
  for (const LabelledCode& c : binary) {
    if (c.code.length != length) {
      problems.push_back(fmt::format("{}: {} bits, but other binary codes have {}", c.label, c.code.length, length));
    }
  }
  if (!problems.empty()) {
    for (const std::string& p : problems) codebook_error(fmt::format("{}: {}", a.file, p));
    return kExitCheckFailed;
  }
  const CodeTiming timing = file.timebase.synchronized ? CodeTiming::kSynchronized : CodeTiming::kFreeRunning;
  auto spec = codebook_spec(a.constraints, timing, file.modulation.kind, static_cast<int>(length));
  if (!spec) {
    codebook_error(spec.error().message);
    return kExitUsage;
  }
  if (a.constraints.length && *a.constraints.length != static_cast<int>(length)) {
    codebook_error(fmt::format("{}: codes have {} bits, not {} (--length)", a.file, length, *a.constraints.length));
    return kExitCheckFailed;
  }
  std::vector<uint64_t> codes;
  std::vector<std::string> labels;
  for (const LabelledCode& c : binary) {
    codes.push_back(c.code.bits);
    labels.push_back(c.label);
  }

  constexpr size_t kShown = 20;
  size_t faults = 0;
  uint32_t closest = spec->length + 1;
  auto note = [&](const CodebookReport& r) {
    if (r.ok()) return;
    if (faults++ < kShown) codebook_error(fmt::format("{}: {}", a.file, fault_text(r, *spec, labels, codes)));
  };
  for (size_t i = 0; i < codes.size(); ++i) note(protocol::check_code(*spec, codes[i], static_cast<uint16_t>(i)));
  for (size_t i = 0; i < codes.size(); ++i) {
    for (size_t j = i + 1; j < codes.size(); ++j) {
      const CodebookReport r =
          protocol::check_pair(*spec, codes[i], static_cast<uint16_t>(i), codes[j], static_cast<uint16_t>(j));
      note(r);
      const uint32_t d = timing == CodeTiming::kFreeRunning
                             ? protocol::cyclic_distance(codes[i], codes[j], spec->length).distance
                             : protocol::hamming_distance(codes[i], codes[j]);
      closest = std::min(closest, d);
    }
  }
  if (faults > 0) {
    if (faults > kShown) codebook_error(fmt::format("{}: ... and {} more", a.file, faults - kShown));
    codebook_error(fmt::format("{}: {} of {} fail: {}", a.file, faults, what, describe_codebook_spec(*spec)));
    return kExitCheckFailed;
  }
  fmt::print("{}: {} pass: {}{}\n", a.file, what, describe_codebook_spec(*spec),
             codes.size() > 1 ? fmt::format("; closest pair at distance {}", closest) : std::string());
  return kExitOk;
}

int run_check(const CheckArgs& a) {
  auto file = read_targets_yaml(a.file);
  if (!file) {
    codebook_error(file.error().what());
    return kExitBadInput;
  }
  if (file->modulation.kind == ModulationKind::kConstant) {
    codebook_error(fmt::format("{}: modulation.kind is constant, so its LEDs play no codes", a.file));
    return kExitCheckFailed;
  }
  std::vector<std::string> problems;
  for (size_t i = 0; i < file->targets.size(); ++i) {
    for (size_t k = 0; k < kMarkers; ++k) {
      if (!file->targets[i].markers[k].code) {
        problems.push_back(fmt::format("targets[{}] (id {}) marker {}: no code (it would emit constantly and cannot "
                                       "be identified)",
                                       i, file->targets[i].id, k));
      }
    }
  }
  if (!problems.empty()) {
    for (const std::string& p : problems) codebook_error(fmt::format("{}: {}", a.file, p));
    return kExitCheckFailed;
  }
  const bool same_within_targets = std::all_of(file->targets.begin(), file->targets.end(), [](const Target& t) {
    return std::all_of(t.markers.begin(), t.markers.end(),
                       [&](const Marker& m) { return *m.code == *t.markers[0].code; });
  });
  const bool per_target = a.per == "target" || (a.per == "auto" && same_within_targets);
  if (per_target && !same_within_targets) {
    codebook_error(fmt::format("{}: --per target, but some target's markers play different codes", a.file));
    return kExitCheckFailed;
  }

  // Square waves are frequency codes (SPEC.md §8.5), as the localizer reads them
  // (localizer/frequency_identifier.hpp); every other code is a binary word.
  std::vector<LabelledCode> binary, frequency;
  for (size_t i = 0; i < file->targets.size(); ++i) {
    const Target& t = file->targets[i];
    for (size_t k = 0; k < (per_target ? 1 : kMarkers); ++k) {
      const Code& code = *t.markers[k].code;
      LabelledCode c{code, per_target ? fmt::format("targets[{}] (id {})", i, t.id)
                                      : fmt::format("targets[{}] (id {}) marker {}", i, t.id, k)};
      (protocol::is_square_wave(code) ? frequency : binary).push_back(std::move(c));
    }
  }
  if (binary.size() > 0xFFFF || frequency.size() > 0xFFFF) {
    codebook_error(fmt::format("{}: more than 65535 codes", a.file));
    return kExitCheckFailed;
  }
  const bool mixed = !binary.empty() && !frequency.empty();
  auto what = [&](size_t n, const char* family) {
    return fmt::format("{} {}codes (one per {})", n, mixed ? family : "", per_target ? "target" : "marker");
  };
  int exit = kExitOk;
  if (!binary.empty()) exit = check_binary_family(a, *file, binary, what(binary.size(), "binary "));
  if (!frequency.empty()) {
    const int f = check_frequency_family(a.file, *file, a.frequency, frequency, binary,
                                         what(frequency.size(), "frequency "));
    exit = exit == kExitOk ? f : exit;
  }
  return exit;
}

}  // namespace

void add_codebook_check_command(CLI::App* codebook, int* result) {
  auto* check = codebook->add_subcommand(
      "check",
      "Check the codes of a targets.yaml against the codebook constraints: binary words by the binary rules, square "
      "waves (frequency codes) at the camera given by --fps and --exposure, and both families apart in a mixed file");
  check->footer(kCodebookDefaultsHelp);
  auto chk = std::make_shared<CheckArgs>();
  check->add_option("file", chk->file, "targets.yaml to check")->required();
  check->add_option("--per", chk->per, "marker, target, or auto (target when each target's markers share a code)")
      ->check(CLI::IsMember({"auto", "marker", "target"}))
      ->capture_default_str();
  add_codebook_constraint_options(check, &chk->constraints);
  add_frequency_camera_options(check, &chk->frequency);

  check->callback([result, chk] { *result = run_check(*chk); });
}

}  // namespace tetrapulse::cli
