// The stability suite's runner and page (issue 11): runs a list of StabilityCase (stability_case.h), one row
// per measure, and writes docs/stability.md: a generated header (command, device, date, load), then per
// family a table (case, method, measure, value, bound, pass/FAIL, note) and the cases' pictures.
#pragma once

#include <string>
#include <vector>

#include "stability/stability_case.h"

namespace voxr {

// Every case of the suite, the families in page order (voxelization, rendering, inputs; temporal joins when
// merged): the one list of the suite's families.
std::vector<StabilityCase> all_stability_cases();

struct StabilityCaseResult {
  const StabilityCase* source = nullptr;
  std::vector<StabilityRow> rows;
  double seconds = 0.0;  // wall time of the case
};

// Runs every case in order. A case that throws gets one failing row recording the exception's text (a
// crash of the suite would hide the other cases); `ctx.progress` gets one line per case.
std::vector<StabilityCaseResult> run_stability_cases(const std::vector<StabilityCase>& cases,
                                                     StabilityContext& ctx);

// The rows of `results` that break their bound (or state no reason for it), one line each ("family name
// method: measure value outside bound (note; bound: reason)"); empty when all pass.
std::vector<std::string> stability_failures(const std::vector<StabilityCaseResult>& results);

struct StabilityHeader {
  std::string command;  // the command line that regenerates the page
  std::string device;
  std::string date;  // UTC, ISO 8601
  std::string load;  // load averages when the suite ran
};

// The Markdown page: header, then per family (in order of first appearance) the cases' descriptions, one
// table of all their rows (with each bound's reason), and their pictures (paths relative to `picture_link`,
// the folder the page links pictures from).
std::string stability_markdown(const std::vector<StabilityCaseResult>& results, const StabilityHeader& header,
                               const std::string& picture_link);

// Formats a value or bound for the tables: integers as such, others with 4 significant digits.
std::string format_stability_number(double v);

// A row's bound as the page shows it: "≤ b", "≥ b", or "low to b" for a documented failure's range.
std::string bound_text(const StabilityRow& row);

}  // namespace voxr
