#pragma once
// The human side of `ambid audit`: an HTML page with the verdict in plain words, the tables of
// audit.json, and SVG plots (services/report) of the time traces and the residual spectra.
#include <string>

#include "diagnostics/audit.hpp"

namespace ambid::cli {

// A standalone HTML document (inline SVG, no scripts, no external resources).
std::string audit_report_html(const diag::AuditResult& result, const std::string& experiment_name);

// The verdict in one or two plain sentences.
std::string audit_verdict(const diag::AuditResult& result);

}  // namespace ambid::cli
