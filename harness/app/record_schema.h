#pragma once
// The whole record schema: the harness's own columns (harness/records/columns.h) and every
// pass's declared columns (Pass columns(), pass_columns()), put together once. `ldmbench
// columns` prints it; the records table in the docs is generated from it and a test checks
// that every column of a real run is described.
#include <string>
#include <vector>

#include "harness/records/columns.h"

namespace ldm {

// The harness's columns with each pass's inserted where the pass group stands (before the
// census); a column several passes write (d_max) once.
const std::vector<ColumnSpec>& record_columns();
// The spec describing `column` (exact names first, then patterns), or null.
const ColumnSpec* find_column(const std::string& column);
std::string columns_markdown();
std::string columns_text();

}  // namespace ldm
