#pragma once
// What `mvw pacs` prints: the matches of a find (a table or JSON lines) and a transfer's summary.
#include <ostream>
#include <string>
#include <vector>

#include "mvw/pacs/Pacs.h"

namespace mvw::pacs {

// The matches of `mvw pacs find`: one JSON object a line (json), or a table with a header
// line, of a study's series (series) or of studies; each column as wide as its longest value
// up to a cap, a longer value cut with "...".
void printMatches(std::ostream& out, const std::vector<Match>& matches, bool json, bool series);

// "stored 3 instances, 1.2 MB in 0.05 s (24.0 MB/s)": what `mvw pacs get|store` and --store
// print.
std::string transferSummary(const char* verb, const Transfer& t);

}  // namespace mvw::pacs
