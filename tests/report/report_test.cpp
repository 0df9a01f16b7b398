// `ldmbench report`: the report of a small run (built here: tiny sizes, seconds) holds every
// plot the data supports, each a non-empty PNG; its pages link only files that exist; a plot
// whose axis takes one value is skipped with a note; the figures regenerate from tidy.csv
// alone; lossy records are flagged, never ranked; bad arguments exit 2 before anything is
// written (and before Python starts).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

using test::ldmbench;
Outcome shell(const std::string& command) { return test::run_shell(command); }

std::string script() {
  return (fs::path(LDM_TEST_SOURCE_DIR) / ".." / "scripts" / "report" / "ldmbench_report.py").string();
}

using test::read_text;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) lines.push_back(line);
  return lines;
}

// Two structures (ppfla made lossy by k = 3 < the Cornell box's depth 6) and HBAO, at two
// view counts and one R_LDM: 5 records, a trade-off, memory and cost against N, no R_LDM range.
fs::path small_run() {
  const fs::path run = fs::path(test::make_temp_dir("ldm-report-run")) / "run";
  const Outcome o = ldmbench(
      "run --scene cornell --structure psppsll,ppfla --pass ao,hbao -N 4,8 -R 32 --width 32 "
      "--height 32 --frames 2 --warmup 1 --time-target 0 --reference-spp 16 --param ppfla:k=3 --cache-dir " +
      test::make_temp_dir("ldm-report-cache") + " --out " + run.string());
  EXPECT_EQ(o.status, 0) << o.output;
  return run;
}

struct Report {
  fs::path run, dir;
  nlohmann::json manifest;
  std::set<std::string> figure_names() const {
    std::set<std::string> names;
    for (const auto& f : manifest["figures"]) names.insert(f["name"].get<std::string>());
    return names;
  }
};

Report small_report(const std::string& options = "") {
  Report r;
  r.run = small_run();
  r.dir = fs::path(test::make_temp_dir("ldm-report")) / "report";
  const Outcome o = ldmbench("report " + r.run.string() + " --out " + r.dir.string() + " " + options);
  EXPECT_EQ(o.status, 0) << o.output;
  r.manifest = nlohmann::json::parse(read_text(r.dir / "manifest.json"));
  return r;
}

const std::set<std::string> kExpectedFigures = {
    "tradeoff-time-vs-mse", "tradeoff-time-vs-mssim", "memory-vs-n_views", "subpasses-cornell",
    "cost-vs-n_views",      "cost-vs-fragments",      "grid-cornell-n_views", "depth-histograms"};

void expect_non_empty_figures(const fs::path& dir, const nlohmann::json& manifest) {
  for (const auto& figure : manifest["figures"])
    for (const auto& file : figure["files"]) {
      const fs::path path = dir / file.get<std::string>();
      ASSERT_TRUE(fs::is_regular_file(path)) << path;
      EXPECT_GT(fs::file_size(path), 1000u) << path;
      if (path.extension() == ".svg")
        EXPECT_NE(read_text(path).find("<svg"), std::string::npos) << path;
      else if (path.extension() == ".pdf")
        EXPECT_EQ(read_text(path).substr(0, 5), "%PDF-") << path;
      else
        EXPECT_EQ(read_text(path).substr(0, 8), "\x89PNG\r\n\x1a\n") << path;
    }
}

void expect_every_plot(const Report& r) {
  SCOPED_TRACE("every plot the data supports, each a non-empty PNG");
  EXPECT_EQ(r.figure_names(), kExpectedFigures);
  expect_non_empty_figures(r.dir, r.manifest);
  size_t pngs = 0;
  for (const auto& entry : fs::directory_iterator(r.dir / "figures"))
    pngs += entry.path().extension() == ".png";
  EXPECT_EQ(pngs, kExpectedFigures.size()) << "a figure on disk the manifest does not list";
}

void expect_tidy_csv_of_every_record(const Report& r) {
  SCOPED_TRACE("tidy.csv: every record and column, the run in front");
  const auto records = lines_of(read_text(r.run / "records.csv"));
  const auto tidy = lines_of(read_text(r.dir / "tidy.csv"));
  ASSERT_EQ(records.size(), 6u);  // header + 5 configurations
  ASSERT_EQ(tidy.size(), records.size());
  EXPECT_EQ(tidy[0], "run,run_dir," + records[0]);
  for (size_t i = 1; i < tidy.size(); ++i)
    EXPECT_EQ(tidy[i], "run,../../" + r.run.parent_path().filename().string() + "/run," + records[i])
        << "row " << i;
}

void expect_links_to_existing_files_only(const Report& r) {
  SCOPED_TRACE("the pages link only files of the report that exist");
  const std::string html = read_text(r.dir / "index.html");
  const std::regex link(R"((?:src|href)=\"([^\"]*)\")");
  size_t links = 0, images = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it) {
    const std::string target = (*it)[1];
    ++links;
    images += target.rfind("figures/", 0) == 0;
    EXPECT_EQ(target.find(':'), std::string::npos) << "not a relative link: " << target;
    EXPECT_NE(target.front(), '/') << "absolute link: " << target;
    EXPECT_EQ(target.find(".."), std::string::npos) << "link out of the report: " << target;
    EXPECT_TRUE(fs::is_regular_file(r.dir / target)) << "missing: " << target;
    if (fs::is_regular_file(r.dir / target)) EXPECT_GT(fs::file_size(r.dir / target), 0u) << target;
  }
  EXPECT_GE(images, kExpectedFigures.size()) << "every figure is shown";
  EXPECT_GE(links, images + 2);  // tidy.csv and summary.md
  for (const auto& figure : r.manifest["figures"])
    for (const auto& file : figure["files"])
      EXPECT_NE(html.find("\"" + file.get<std::string>() + "\""), std::string::npos) << "not linked: " << file;
  const std::string md = read_text(r.dir / "summary.md");
  const std::regex md_image(R"(!\[[^\]]*\]\(([^)]*)\))");
  size_t md_images = 0;
  for (auto it = std::sregex_iterator(md.begin(), md.end(), md_image); it != std::sregex_iterator(); ++it, ++md_images)
    EXPECT_TRUE(fs::is_regular_file(r.dir / std::string((*it)[1]))) << (*it)[1];
  EXPECT_EQ(md_images, kExpectedFigures.size());
}

void expect_skipped_plots_noted(const Report& r) {
  SCOPED_TRACE("a plot over a single-valued axis is skipped with a note");
  // R_LDM took one value (32): no memory or cost plot against it, a note in both pages.
  EXPECT_FALSE(fs::exists(r.dir / "figures" / "memory-vs-r_ldm.png"));
  EXPECT_FALSE(fs::exists(r.dir / "figures" / "cost-vs-r_ldm.png"));
  for (const char* page : {"summary.md", "index.html"}) {
    const std::string text = read_text(r.dir / page);
    EXPECT_NE(text.find("memory vs R_LDM: skipped, R_LDM takes fewer than two values (32)"),
              std::string::npos) << page;
    EXPECT_NE(text.find("cost vs R_LDM: skipped"), std::string::npos) << page;
  }
}

void expect_lossy_records_flagged_not_ranked(const Report& r) {
  SCOPED_TRACE("lossy records are flagged, never ranked");
  const std::string md = read_text(r.dir / "summary.md");
  const size_t best = md.find("## Best per criterion");
  const size_t flagged = md.find("## Flagged configurations (2: not ranked)");
  ASSERT_NE(best, std::string::npos) << md;
  ASSERT_NE(flagged, std::string::npos) << md;
  const std::string best_table = md.substr(best, flagged - best);
  EXPECT_NE(best_table.find("| fastest build |"), std::string::npos) << best_table;
  EXPECT_NE(best_table.find("| best mssim |"), std::string::npos) << best_table;
  EXPECT_NE(best_table.find("| least memory allocated |"), std::string::npos) << best_table;
  EXPECT_EQ(best_table.find("ppfla"), std::string::npos) << "a lossy record ranked:\n" << best_table;
  const std::string flagged_table = md.substr(flagged, md.find("## Notes") - flagged);
  EXPECT_NE(flagged_table.find("cornell-ppfla-ao-n4-r32-plane-k=3-prevframe | lossy"),
            std::string::npos) << flagged_table;
  EXPECT_NE(read_text(r.dir / "index.html").find("<tr class=\"flagged\">"), std::string::npos);
}

// One report for several properties: each TEST builds its run and report (seconds), and
// ctest runs every TEST in its own process.
TEST(Report, OfASmallRunHoldsEveryPlotAndEveryRecord) {
  const Report r = small_report();
  expect_every_plot(r);
  expect_tidy_csv_of_every_record(r);
  expect_lossy_records_flagged_not_ranked(r);
}

TEST(Report, PagesLinkOnlyExistingFilesAndNoteSkippedPlots) {
  const Report r = small_report("--svg");  // the pages link the SVGs too
  expect_non_empty_figures(r.dir, r.manifest);
  expect_links_to_existing_files_only(r);
  expect_skipped_plots_noted(r);
}

TEST(Report, RegeneratesEveryFigureFromTheTidyCsvAlone) {
  const Report r = small_report();
  // tidy.csv alone, the run folder gone: every figure but the image grids comes back.
  const fs::path alone = fs::path(test::make_temp_dir("ldm-report-csv"));
  fs::copy_file(r.dir / "tidy.csv", alone / "tidy.csv");
  fs::copy_file(r.dir / "axes.json", alone / "axes.json");  // the axes the report was made with
  fs::remove_all(r.run);
  const fs::path again = alone / "again";
  const Outcome o = shell(std::string(LDM_PYTHON) + " " + script() + " --from-csv " +
                          (alone / "tidy.csv").string() + " --out " + again.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto manifest = nlohmann::json::parse(read_text(again / "manifest.json"));
  std::set<std::string> names;
  for (const auto& f : manifest["figures"]) names.insert(f["name"].get<std::string>());
  std::set<std::string> expected = kExpectedFigures;
  expected.erase("grid-cornell-n_views");
  EXPECT_EQ(names, expected);
  expect_non_empty_figures(again, manifest);
  EXPECT_NE(read_text(again / "summary.md").find("image grids: skipped, the runs' images are not there"),
            std::string::npos);
  EXPECT_EQ(lines_of(read_text(again / "tidy.csv")).size(), 6u);

  // Into the same folder again: the earlier report is replaced (what its manifest lists,
  // e.g. a figure no longer drawn, goes), anything else there stays.
  auto earlier = manifest;
  earlier["files"].push_back("figures/dropped.png");
  std::ofstream(again / "manifest.json") << earlier.dump();
  std::ofstream(again / "figures" / "dropped.png") << "old";
  std::ofstream(again / "mine.txt") << "not the report's";
  const Outcome replaced = shell(std::string(LDM_PYTHON) + " " + script() + " --from-csv " +
                                 (alone / "tidy.csv").string() + " --out " + again.string());
  ASSERT_EQ(replaced.status, 0) << replaced.output;
  EXPECT_FALSE(fs::exists(again / "figures" / "dropped.png"));
  EXPECT_TRUE(fs::exists(again / "mine.txt"));
  EXPECT_TRUE(fs::is_regular_file(again / "index.html"));
}

// Errors compare only between records scored against the same reference: AO and indirect
// light (or AO at two d_max) estimate different images, so each gets its own ranking.
// Records from the committed default report: AO (an LDM structure and HBAO) and indirect
// light on the Cornell box.
TEST(Report, RanksErrorsOnlyAmongRecordsOfTheSameReference) {
  const std::string tidy =
      read_text(fs::path(LDM_TEST_SOURCE_DIR) / ".." / "docs" / "reports" / "default" / "tidy.csv");
  const std::vector<std::string> lines = lines_of(tidy);
  ASSERT_FALSE(lines.empty());
  const fs::path dir = fs::path(test::make_temp_dir("ldm-report-groups"));
  {
    std::ofstream subset(dir / "tidy.csv");
    subset << lines[0] << "\n";
    int kept = 0;
    for (const char* id : {",cornell-psppsll-ao-n32-r128-plane-prevframe,", ",cornell-none-hbao,",
                           ",cornell-psppsll-indirect-n16-r64-plane-r_light=64-prevframe,"})
      for (const auto& line : lines)
        if (line.find(id) != std::string::npos) subset << line << "\n", ++kept;
    ASSERT_EQ(kept, 3) << "the committed report no longer holds the three records";
  }
  // The committed report's axes (axes.json beside its tidy.csv) are not copied: the axis
  // registry comes from the binary, as `ldmbench report` passes it.
  ASSERT_EQ(shell(std::string(LDM_BINARY_PATH) + " axes --json > " + (dir / "axes.json").string()).status, 0);
  const Outcome o = shell(std::string(LDM_PYTHON) + " " + script() + " --from-csv " +
                          (dir / "tidy.csv").string() + " --out " + (dir / "report").string() +
                          " --dpi 20");
  ASSERT_EQ(o.status, 0) << o.output;
  std::vector<std::string> lowest_mse;
  for (const auto& line : lines_of(read_text(dir / "report" / "summary.md")))
    if (line.rfind("| lowest mse |", 0) == 0) lowest_mse.push_back(line);
  ASSERT_EQ(lowest_mse.size(), 2u) << "AO and indirect light ranked together";
  for (const auto& row : lowest_mse) {
    const bool indirect_group = row.find(": indirect |") != std::string::npos;
    EXPECT_EQ(row.find("-indirect-") != std::string::npos, indirect_group) << row;
  }
}

// Bad input: exit 2, a message naming the culprit, `out` not created.
void expect_rejected(const std::string& args, const std::string& culprit, const fs::path& out,
                     const std::string& environment = "") {
  const Outcome o = ldmbench("report " + args + " --out " + out.string(), environment);
  EXPECT_EQ(o.status, 2) << args << "\n" << o.output;
  EXPECT_NE(o.output.find(culprit), std::string::npos) << args << "\n" << o.output;
  EXPECT_FALSE(fs::exists(out)) << args << ": the report folder was created";
}

TEST(Report, RejectsBadArgumentsBeforeWritingAnything) {
  const fs::path dir = test::make_temp_dir("ldm-report-bad");
  const fs::path out = dir / "out";
  fs::create_directories(dir / "empty");
  std::ofstream(dir / "garbage.json") << "{\"not\": \"records\"}";
  std::ofstream(dir / "torn.json") << "{\"records\": [";
  std::ofstream(dir / "other.csv") << "a,b\n1,2\n";
  std::ofstream(dir / "notes.txt") << "hello\n";
  fs::create_directories(dir / "good");
  std::ofstream(dir / "good" / "records.csv") << "config_id,status\nx,ok\n";
  expect_rejected((dir / "missing").string(), (dir / "missing").string() + ": no such file", out);
  expect_rejected((dir / "empty").string(), "without records.csv or records.json", out);
  expect_rejected((dir / "garbage.json").string(), "garbage.json: not an ldmbench records.json", out);
  expect_rejected((dir / "torn.json").string(), "torn.json: malformed JSON", out);
  expect_rejected((dir / "other.csv").string(), "other.csv: not ldmbench records (no column config_id)", out);
  expect_rejected((dir / "notes.txt").string(), "notes.txt: expected a run folder", out);
  // a bad run among good ones is found before anything happens
  expect_rejected((dir / "good").string() + " " + (dir / "missing").string(), "missing: no such file", out);
  // --out holding something that is not a report is not overwritten
  fs::create_directories(out / "mine");
  const Outcome taken = ldmbench("report " + (dir / "good").string() + " --out " + out.string());
  EXPECT_EQ(taken.status, 2) << taken.output;
  EXPECT_NE(taken.output.find("is not empty and holds no earlier report"), std::string::npos) << taken.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
  fs::remove_all(out);
  const Outcome into_run = ldmbench("report " + (dir / "good").string() + " --out " + (dir / "good").string());
  EXPECT_EQ(into_run.status, 2) << into_run.output;
  EXPECT_NE(into_run.output.find("--out: '" + (dir / "good").string() + "' is the folder of"), std::string::npos)
      << into_run.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "good"), fs::directory_iterator()), 1);
  const Outcome several = ldmbench("report " + (dir / "good").string() + " " + (dir / "good" / "records.csv").string());
  EXPECT_EQ(several.status, 2) << several.output;
  EXPECT_NE(several.output.find("--out: needed when reporting several runs"), std::string::npos);
  // no usable Python, or no script: said so, with the remedy
  expect_rejected((dir / "good").string(), "scripts/setup.sh", out, "LDMBENCH_PYTHON=" + (dir / "nopython").string());
  const fs::path no_matplotlib = dir / "python-without-matplotlib";
  std::ofstream(no_matplotlib) << "#!/bin/sh\necho \"ModuleNotFoundError: No module named 'matplotlib'\" >&2\nexit 1\n";
  fs::permissions(no_matplotlib, fs::perms::owner_all);
  expect_rejected((dir / "good").string(), no_matplotlib.string() + ": ModuleNotFoundError: No module named 'matplotlib'",
                  out, "LDMBENCH_PYTHON=" + no_matplotlib.string());
  expect_rejected((dir / "good").string(), "LDMBENCH_REPORT_SCRIPT=" + (dir / "none.py").string() + ": no such file",
                  out, "LDMBENCH_REPORT_SCRIPT=" + (dir / "none.py").string());
  // the script checks the same on its own
  for (const std::string& args : {(dir / "garbage.json").string(), "--from-csv " + (dir / "other.csv").string(),
                                  "--from-csv " + (dir / "missing.csv").string()}) {
    const Outcome o = shell(std::string(LDM_PYTHON) + " " + script() + " " + args + " --out " + out.string());
    EXPECT_EQ(o.status, 2) << args << "\n" << o.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

// --format: every figure in each format asked for (PDF and SVG for a paper); the pages
// open with the front table ("Choose a structure"), the details after it.
TEST(Report, WritesEveryFigureInEveryFormatAndOpensWithTheFrontTable) {
  const Report r = small_report("--format png,pdf --format svg");
  expect_non_empty_figures(r.dir, r.manifest);
  EXPECT_EQ(r.figure_names(), kExpectedFigures);
  for (const auto& figure : r.manifest["figures"]) {
    std::set<std::string> extensions;
    for (const auto& file : figure["files"]) extensions.insert(fs::path(file.get<std::string>()).extension());
    EXPECT_EQ(extensions, (std::set<std::string>{".png", ".pdf", ".svg"})) << figure["name"];
  }
  const std::string md = read_text(r.dir / "summary.md");
  const size_t first_section = md.find("\n## ");
  ASSERT_NE(first_section, std::string::npos);
  EXPECT_EQ(md.substr(first_section, 22), "\n## Choose a structure") << md.substr(0, 400);
  EXPECT_LT(md.find("| compared within | configuration |"), md.find("## Best per criterion"));
  EXPECT_NE(md.find("| cornell: ao/hbao at d_max"), std::string::npos) << md.substr(0, 2000);
  // the lossy ppfla records are flagged, never on the front
  const std::string front = md.substr(0, md.find("## Runs"));
  EXPECT_EQ(front.find("ppfla"), std::string::npos) << front;
  // a format the report does not know: exit 2 before anything is written
  const fs::path out = fs::path(test::make_temp_dir("ldm-report-format")) / "out";
  expect_rejected(r.run.string() + " --format png,tiff", "--format: 'tiff' is not one of png, svg, pdf", out);
}

// What the figures and the front table show, on hand-made tables (issue 23's items:
// labelled points and run markers, grey AO, tone-mapped HDR, one reference per pass,
// slopes from three points, merged coinciding lines, the title scheme, formats, sizes).
TEST(ReportFigures, ShowWhatAPaperNeeds) {
  const Outcome o = shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR + "/report/test_figures.py");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("OK"), std::string::npos) << o.output;
}

// No overlapping text (issue 37): the figures of real runs, the small Cornell run above and
// one structure on a mesh file (a title that wraps over a narrow image grid, a d_max derived
// from the model's size), drawn by the report while tests/report/check_text_overlap.py
// takes matplotlib's own bounding box of every drawn text and names any two that overlap.
TEST(ReportFigures, NoTextOverlapsInTheFiguresOfRealRuns) {
  const fs::path cornell = small_run();
  const fs::path dir = test::make_temp_dir("ldm-report-overlap");
  const Outcome mesh = ldmbench("run --scene " + std::string(LDM_TEST_SOURCE_DIR) +
                                "/../scenes/meshes/torus_knot.obj --structure psppsll -N 4,8 -R 32 --width 64 "
                                "--height 64 --frames 2 --warmup 1 --time-target 0 --reference-spp 16 --cache-dir " +
                                (dir / "cache").string() + " --out " + (dir / "knot").string());
  ASSERT_EQ(mesh.status, 0) << mesh.output;
  const Outcome axes = shell(std::string(LDM_BINARY_PATH) + " axes --json > " + (dir / "axes.json").string());
  ASSERT_EQ(axes.status, 0) << axes.output;
  int report = 0;
  for (const std::string runs : {cornell.string() + " " + (dir / "knot").string(), (dir / "knot").string()}) {
    const std::string out = (dir / ("report-" + std::to_string(++report))).string();
    const Outcome o = shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR + "/report/check_text_overlap.py " +
                            runs + " --axes " + (dir / "axes.json").string() + " --out " + out);
    EXPECT_EQ(o.status, 0) << o.output;
    EXPECT_NE(o.output.find("figures checked: tradeoff-time-vs-mse"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("grid-torus_knot-n_views"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("OVERLAP"), std::string::npos) << o.output;
  }
}

// The ties of rankings and fronts, and the time digits, on hand-made tables
// (tests/report/test_ties.py, Python's unittest).
TEST(ReportTies, TiesAreShownAsTies) {
  const Outcome o = shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR + "/report/test_ties.py");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("OK"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace ldm
