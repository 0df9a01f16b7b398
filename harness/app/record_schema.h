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
// The columns every record carries, a failed one's included (describe_configuration, then
// wall_seconds): a journal record without one of them is not a record of its build.
const std::vector<std::string>& always_written_columns();
// What a run's journal entry declares of the build that wrote it (schema_columns,
// schema_always_written: names, space-separated), so that `ldmbench merge` of any later build
// checks each record against its own build's schema (record_validation.h).
std::string declared_columns_text();
std::string always_written_columns_text();
std::string columns_markdown();
std::string columns_text();

}  // namespace ldm
