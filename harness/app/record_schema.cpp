#include "harness/app/record_schema.h"

#include <algorithm>
#include <set>

#include "harness/passes/pass.h"

namespace ldm {

const std::vector<ColumnSpec>& record_columns() {
  static const std::vector<ColumnSpec> columns = [] {
    std::vector<ColumnSpec> passes;
    std::set<std::string> seen;
    for (const auto& name : pass_names())
      for (ColumnSpec c : pass_columns(name)) {
        if (!seen.insert(c.name).second) continue;
        c.group = "pass";
        passes.push_back(std::move(c));
      }
    std::vector<ColumnSpec> all = harness_record_columns();
    const auto census = std::find_if(all.begin(), all.end(), [](const ColumnSpec& c) { return c.group == "census"; });
    all.insert(census, passes.begin(), passes.end());
    return all;
  }();
  return columns;
}

const ColumnSpec* find_column(const std::string& column) { return find_column_in(record_columns(), column); }

std::string columns_markdown() { return columns_markdown(record_columns()); }

std::string columns_text() { return columns_text(record_columns()); }

}  // namespace ldm
