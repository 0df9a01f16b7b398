#pragma once
// The whole record schema: the harness's own columns (harness/records/columns.h) and every
// pass's declared columns (Pass columns(), pass_columns()), put together once. `ldmbench
// columns` prints it; the records table in the docs is generated from it and a test checks
// that every column of a real run is described.
#include <string>
#include <vector>

#include "harness/measure/work_counters.h"
#include "harness/records/columns.h"
#include "harness/records/record.h"

namespace ldm {

// The harness's columns with each pass's inserted where the pass group stands (before the
// census); a column several passes write (d_max) once.
const std::vector<ColumnSpec>& record_columns();
// The work counters a configuration's counting replay records (its work_* columns, which
// record_columns() holds for every structure and pass): the structure's and the census
// sizing policy's (none for a peer pass, `structure` "none"), then the pass's.
std::vector<WorkCounter> configuration_work_counters(const std::string& structure, const std::string& pass);
// The spec describing `column` (exact names first, then patterns), or null.
const ColumnSpec* find_column(const std::string& column);
// Whether `column` is declared: described by the schema (a pattern's included) or the record
// column of a harness axis (harness/settings/harness_axes.h; a test's or an extension's axis too).
bool is_declared_column(const std::string& column);
// An empty record of a measured configuration: it refuses an undeclared column (Record::set
// throws std::logic_error naming it).
Record measurement_record();

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
std::string columns_json();

}  // namespace ldm
