// The axis registry (harness/settings/harness_axes.h, harness/settings/axis_registry.h): every axis
// declared once, by its owner, and everything else derived from the declaration. The proof
// is an axis added here, in a test, touching nothing but its own declaration: a harness axis
// and a pass with a parameter of its own reach the command line, sweep files, the product,
// the ids, the re-serialised command line, the sweep file a viewer saves, `ldmbench axes`,
// and the identity.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <map>
#include <set>

#include "harness/settings/axis_options.h"
#include "harness/settings/axis_registry.h"
#include "harness/settings/harness_axes.h"
#include "harness/measuring/measure_configuration.h"
#include "harness/run/memory_plan.h"
#include "harness/settings/record_schema.h"
#include "harness/settings/run_command_line.h"
#include "harness/run/sweep_plan.h"
#include "harness/run/sweep_spec.h"
#include "harness/passes/ambient_occlusion.h"
#include "harness/passes/pass.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "ldm_impls/ldm_structure.h"
#include "tests/support/test_support.h"

namespace ldm {
namespace {

// A harness axis no consumer in the code knows: declared here and nowhere else. Its values
// live in RunSettings::axis_lists (no binding); its consumer would read Configuration::values.
void declare_test_gain_axis() {
  if (find_harness_axis("test_gain")) return;
  HarnessAxis axis;
  axis.spec.key = "test_gain";
  axis.spec.label = "gain";
  axis.spec.flags = "--test-gain";
  axis.spec.kind = AxisKind::Real;
  axis.spec.min = 0.5;
  axis.spec.max = 4;
  axis.spec.unit = "x";
  axis.spec.column = "test_gain";  // its record column: written by the axis loop, nowhere else
  axis.spec.description = "a test's axis";
  axis.id_rank = 150;
  axis.id_fragment = [](const AxisValues& values, bool) {
    const auto it = values.find("test_gain");
    return it == values.end() ? std::string() : "-gain" + it->second;
  };
  register_harness_axis(axis);
}

// The AO pass registered, once, as `name`, with `extra` parameters besides its own: declared
// here, beside the test that reads them.
void register_ao_pass_with(const std::string& name, std::vector<AxisSpec> extra) {
  const auto names = pass_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  PassRegistration pass;
  pass.name = name;
  pass.parameters = [extra] {
    std::vector<AxisSpec> specs = AmbientOcclusion::parameters();
    specs.insert(specs.end(), extra.begin(), extra.end());
    return specs;
  };
  pass.columns = AmbientOcclusion::columns;
  pass.make = [](StructureParams& p) { return std::make_unique<AmbientOcclusion>(p); };
  pass.work = AmbientOcclusion::work_counters;  // its shaders count them when measured
  pass.query_subpasses = {"ao"};
  register_pass(pass);
}

// A pass with a parameter of its own, declared beside the pass (here: the AO pass with one
// more parameter it accepts).
void declare_test_pass() {
  register_ao_pass_with("test_ao", {numeric_parameter("boost", AxisKind::UInt, 1, 8, "1", "", "a test pass's parameter")});
}

// A pass whose parameters have record columns of their own, declared here and nowhere else:
// the AO pass (whose describe() knows nothing of them) with an integer, a real and a choice.
void declare_test_columns_pass() {
  register_ao_pass_with(
      "test_columns_ao",
      {numeric_parameter("strength", AxisKind::UInt, 1, 8, "3", "", "a test parameter", "test_strength"),
       numeric_parameter("scale", AxisKind::Real, 0, 1, "0.1", "", "a test parameter", "test_scale"),
       choice_parameter("mode", {"plain", "fancy"}, "plain", "a test parameter", "test_mode")});
}

// A pass that consumes the test axis: the AO pass, reading test_gain where every pass gets
// its configuration (PassInputs::axes), and writing what it read to a column it declares.
// Nothing between the axis's declaration above and this consumer names the axis.
class GainReadingAo : public AmbientOcclusion {
 public:
  using AmbientOcclusion::AmbientOcclusion;
  static std::vector<ColumnSpec> columns() {
    std::vector<ColumnSpec> specs = AmbientOcclusion::columns();
    specs.push_back({"pass", "test_gain_read", "x", "the test axis's value as the pass read it",
                     ColumnKind::Number});
    return specs;
  }
  std::string name() const override { return "test_gain_ao"; }
  void prepare(const PassInputs& in) override {
    AmbientOcclusion::prepare(in);
    gain_read_ = in.axes ? axis_real(*in.axes, "test_gain") : std::nullopt;
  }
  std::vector<std::pair<std::string, RecordValue>> results() const override {
    auto out = AmbientOcclusion::results();
    if (gain_read_) out.emplace_back("test_gain_read", *gain_read_);
    return out;
  }

 private:
  std::optional<double> gain_read_;
};

void declare_gain_reading_pass() {
  const auto names = pass_names();
  if (std::find(names.begin(), names.end(), "test_gain_ao") != names.end()) return;
  PassRegistration pass;
  pass.name = "test_gain_ao";
  pass.parameters = AmbientOcclusion::parameters;
  pass.columns = GainReadingAo::columns;
  pass.make = [](StructureParams& p) { return std::make_unique<GainReadingAo>(p); };
  pass.work = AmbientOcclusion::work_counters;
  pass.query_subpasses = {"ao"};
  register_pass(pass);
}

class Axes : public ::testing::Test {
 protected:
  void SetUp() override {
    declare_test_gain_axis();
    declare_test_pass();
    declare_gain_reading_pass();
    declare_test_columns_pass();
  }
};

// The command line of `ldmbench run` as its options are made from the declarations.
RunSettings parsed(std::vector<std::string> args) {
  CLI::App app;
  AxisOptions axes;
  add_axis_options(&app, axes);
  std::vector<std::string> params;
  app.add_option("--param", params);
  std::reverse(args.begin(), args.end());  // CLI11 parses a reversed vector
  app.parse(args);
  RunSettings s;
  apply_axis_options(axes, s);
  for (const auto& p : params) {
    const auto colon = p.find(':'), equals = p.find('=');
    s.structure_params[p.substr(0, colon)][p.substr(colon + 1, equals - colon - 1)] = p.substr(equals + 1);
  }
  return s;
}

std::vector<std::string> ids_of(const std::vector<Configuration>& configs) {
  std::vector<std::string> ids;
  for (const auto& c : configs) ids.push_back(c.id());
  return ids;
}

TEST_F(Axes, AnAxisDeclaredInATestIsAnOptionAnAxisOfTheProductAndPartOfTheId) {
  const RunSettings s = parsed({"--test-gain", "1,2.50", "--pass", "test_ao", "--param", "test_ao:boost=2,3",
                                "-N", "4", "-R", "16"});
  ASSERT_EQ(s.axis_lists.at("test_gain"), (std::vector<std::string>{"1", "2.5"}));  // canonical
  const auto configs = expand_configurations(s);
  const std::vector<std::string> expected = {
      "cornell-psppsll-test_ao-n4-r16-plane-boost=2-prevframe-gain1",
      "cornell-psppsll-test_ao-n4-r16-plane-boost=3-prevframe-gain1",
      "cornell-psppsll-test_ao-n4-r16-plane-boost=2-prevframe-gain2.5",
      "cornell-psppsll-test_ao-n4-r16-plane-boost=3-prevframe-gain2.5"};
  std::vector<std::string> ids = ids_of(configs), sorted = expected;
  std::sort(ids.begin(), ids.end());
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(ids, sorted);
  // The consumer of the new axis reads its value from the configuration.
  EXPECT_EQ(configs.front().values.at("test_gain"), "1");
  EXPECT_EQ(configs.front().pass_params.at("boost"), "2");
  // Bad values are refused by the declaration, naming the option and the range.
  try {
    parsed({"--test-gain", "9"});
    FAIL() << "a gain outside [0.5, 4] was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("--test-gain: gain 9 reads as 9 in a 32-bit float; it must lie in [0.5, 4]"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(expand_configurations(parsed({"--pass", "test_ao", "--param", "test_ao:boost=0"})), UserError);
  // Duplicates are one configuration measured twice: refused.
  EXPECT_THROW(parsed({"--test-gain", "1,1.0"}), UserError);
}

// The carrier from axis to record: the test's axis reaches a measured record's column (and the
// memory plan's) through its declaration alone, typed by its kind, beside the built-in axes'
// identity columns; a record of measurement refuses a column no one declared.
TEST_F(Axes, AnAxisDeclaredInATestReachesTheRecordColumnItNames) {
  const auto configs = expand_configurations(parsed({"--test-gain", "2.5", "-N", "4", "-R", "16"}));
  ASSERT_EQ(configs.size(), 1u);
  Record record = measurement_record();
  describe_configuration(record, configs.front(), RunSettings(), DeviceInfo());
  const RecordValue* gain = record.get("test_gain");
  ASSERT_NE(gain, nullptr) << "the axis's column is not in the record";
  ASSERT_TRUE(std::holds_alternative<double>(*gain));
  EXPECT_EQ(std::get<double>(*gain), 2.5);
  EXPECT_EQ(std::get<int64_t>(*record.get("n_views")), 4);
  EXPECT_EQ(std::get<int64_t>(*record.get("r_ldm")), 16);
  EXPECT_EQ(std::get<std::string>(*record.get("structure")), "psppsll");
  EXPECT_EQ(std::get<int64_t>(*record.get("width")), 256);
  EXPECT_EQ(std::get<int64_t>(*record.get("frames")), 5);
  // The identity columns in the order records have always had.
  std::vector<std::string> keys;
  for (const auto& [key, value] : record.fields()) keys.push_back(key);
  const std::vector<std::string> identity = {"config_id", "status", "status_detail", "scene", "structure",
                                             "pass", "n_views", "r_ldm", "width", "height",
                                             "structure_params", "sizing_policy"};
  ASSERT_GE(keys.size(), identity.size());
  EXPECT_EQ(std::vector<std::string>(keys.begin(), keys.begin() + identity.size()), identity);

  // The memory plan writes the same loop's columns.
  MemoryPlanRow row;
  row.config = configs.front();
  const Record planned = row.to_record();
  ASSERT_NE(planned.get("test_gain"), nullptr);
  EXPECT_EQ(std::get<double>(*planned.get("test_gain")), 2.5);
  EXPECT_EQ(std::get<int64_t>(*planned.get("n_views")), 4);

  // Undeclared: refused at its first use, named.
  try {
    record.set("test_undeclared_column", 1);
    FAIL() << "an undeclared column was accepted";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("test_undeclared_column"), std::string::npos) << e.what();
  }
}

// The smallest measurement of `pass`: no reference, no images, one frame.
RunSettings measured_quickly(std::vector<std::string> args, const std::string& pass) {
  RunSettings settings = parsed(std::move(args));
  settings.passes = {pass};
  settings.width = settings.height = 32;
  settings.frames = 1;
  settings.warmup = 0;
  settings.reference.enabled = false;
  settings.write_images = false;
  return settings;
}

// End to end, measured: the axis's value travels from the command line through the
// configuration into measure(), reaches the pass that reads it, and lands in the record both
// as the axis's own column and as what the pass read, with nothing on the way naming it.
TEST_F(Axes, AnAxisDeclaredInATestReachesThePassThatReadsItAndTheRecord) {
  test::gl_context();
  const RunSettings settings = measured_quickly({"--test-gain", "2.5", "-N", "4", "-R", "16"}, "test_gain_ao");
  const auto configs = expand_configurations(settings);
  ASSERT_EQ(configs.size(), 1u);
  const Scene scene = load_scene("cornell");
  const std::string out = test::make_temp_dir("ldm-axes-measured");
  const Record record = measure_configuration(scene, configs.front(), settings,
                                              test::gl_context().device(), {out, out + "/images"});
  EXPECT_EQ(std::get<std::string>(*record.get("status")), "ok")
      << std::get<std::string>(*record.get("status_detail"));
  ASSERT_NE(record.get("test_gain"), nullptr) << "the axis's column is not in the record";
  EXPECT_EQ(std::get<double>(*record.get("test_gain")), 2.5);
  const RecordValue* read = record.get("test_gain_read");
  ASSERT_NE(read, nullptr) << "the pass did not get the axis's value";
  EXPECT_EQ(std::get<double>(*read), 2.5);

  // A configuration without the axis: the pass reads nothing, and writes nothing.
  const RunSettings plain = measured_quickly({"-N", "4", "-R", "16"}, "test_gain_ao");
  const auto plain_configs = expand_configurations(plain);
  ASSERT_EQ(plain_configs.size(), 1u);
  const Record without = measure_configuration(scene, plain_configs.front(), plain,
                                               test::gl_context().device(), {out, out + "/images"});
  EXPECT_EQ(without.get("test_gain_read"), nullptr);
}

// End to end, measured: a pass parameter declared in a test, with its column, reaches that
// column typed by its kind, from the command line's value or else from its declared default,
// though the pass's describe() (the AO pass's) has never heard of it.
TEST_F(Axes, APassParameterDeclaredInATestReachesItsColumnWithNoDescribe) {
  test::gl_context();
  const RunSettings settings = measured_quickly(
      {"--pass", "test_columns_ao", "--param", "test_columns_ao:strength=5", "--param", "test_columns_ao:mode=fancy",
       "-N", "4", "-R", "16"},
      "test_columns_ao");
  const auto configs = expand_configurations(settings);
  ASSERT_EQ(configs.size(), 1u);
  const Scene scene = load_scene("cornell");
  for (const auto& [column, value] : make_pass("test_columns_ao", StructureParams())->describe(scene))
    EXPECT_TRUE(column.rfind("test_", 0) != 0) << "describe() writes " << column;
  const std::string out = test::make_temp_dir("ldm-axes-parameter-columns");
  const Record record = measure_configuration(scene, configs.front(), settings, test::gl_context().device(),
                                              {out, out + "/images"});
  EXPECT_EQ(std::get<std::string>(*record.get("status")), "ok")
      << std::get<std::string>(*record.get("status_detail"));
  const RecordValue* strength = record.get("test_strength");  // given
  ASSERT_NE(strength, nullptr) << "the parameter's column is not in the record";
  EXPECT_EQ(std::get<int64_t>(*strength), 5);
  const RecordValue* scale = record.get("test_scale");  // its default: the canonical 0.1
  ASSERT_NE(scale, nullptr);
  EXPECT_EQ(std::get<double>(*scale), 0.1);
  const RecordValue* mode = record.get("test_mode");
  ASSERT_NE(mode, nullptr);
  EXPECT_EQ(std::get<std::string>(*mode), "fancy");
  // The AO settings stay the pass's own to write (describe()): the value in effect.
  EXPECT_EQ(std::get<std::string>(*record.get("trace")), "plane");
}

// The built-in passes: describe() writes none of their parameters' own columns but the value in
// effect of a parameter with no declared default where none is given (the indirect pass's a
// and T_foot); pass_parameter_values() writes the others, from the configuration or the default.
TEST_F(Axes, EveryPassParametersColumnIsWrittenOnceFromTheConfiguration) {
  const Scene scene = load_scene("cornell");
  size_t written = 0;
  for (const std::string& name : pass_names()) {
    std::map<std::string, std::string> parameter_of_column;
    for (const AxisSpec& p : pass_parameters(name))
      if (has_parameter_column(p)) parameter_of_column[p.column] = p.key;
    const auto defaults = pass_parameter_values(name, {});
    std::set<std::string> by_default;
    for (const auto& [column, value] : defaults) by_default.insert(column);
    written += defaults.size();
    std::set<std::string> described;
    for (const auto& [column, value] : make_pass(name, StructureParams())->describe(scene)) {
      described.insert(column);
      if (!parameter_of_column.count(column)) continue;
      EXPECT_EQ(by_default.count(column), 0u) << name << ": " << column << " written twice";
      const AxisSpec* p = find_axis(pass_parameters(name), parameter_of_column[column]);
      EXPECT_TRUE(p->default_value.empty()) << name << ": describe() writes " << column;
    }
    for (const auto& [column, key] : parameter_of_column)
      EXPECT_TRUE(by_default.count(column) || described.count(column)) << name << ": " << column << " unwritten";
  }
  EXPECT_GE(written, 20u);
  // Typed by kind, the configuration's canonical value over the default.
  const auto gtao = pass_parameter_values("gtao", {{"gtao:slices", "4"}, {"gtao:radius", "0.1"}, {"hbao:steps", "2"}});
  const std::map<std::string, RecordValue> values(gtao.begin(), gtao.end());
  EXPECT_EQ(values.size(), 10u);
  EXPECT_EQ(std::get<int64_t>(values.at("gtao_slices")), 4);
  EXPECT_EQ(std::get<int64_t>(values.at("gtao_steps")), 16);
  EXPECT_EQ(std::get<double>(values.at("gtao_radius")), 0.1);  // not the float's 0.10000000149011612
  EXPECT_EQ(std::get<std::string>(values.at("gtao_jitter")), "on");
  // A parameter with no default: its value given, the column is the configuration's, and the
  // pass's describe() leaves it alone; not given, the pass writes the value it derives (a = s).
  const auto indirect = pass_parameter_values("indirect", {{"indirect:a", "2"}});
  const std::map<std::string, RecordValue> given(indirect.begin(), indirect.end());
  EXPECT_EQ(std::get<double>(given.at("topological_bias")), 2.0);
  EXPECT_EQ(given.count("footprint_threshold"), 0u);
  const auto pass = make_pass("indirect", StructureParams(std::map<std::string, std::string>{{"a", "2"}}));
  for (const auto& [column, value] : pass->describe(scene)) EXPECT_NE(column, "topological_bias");
  for (const auto& [column, value] : make_pass("indirect", StructureParams())->describe(scene))
    if (column == "topological_bias") EXPECT_EQ(std::get<double>(value), 4.0);  // s's default
  // a = s as s's column holds it: the canonical value of s's text.
  const auto s_given = make_pass("indirect", StructureParams(std::map<std::string, std::string>{{"s", "0.1"}}));
  bool derived = false;
  for (const auto& [column, value] : s_given->describe(scene))
    if (column == "topological_bias") derived = std::get<double>(value) == 0.1;
  EXPECT_TRUE(derived);
}

TEST(AxisValues, TypedAccessorsReadCanonicalTextAndRefuseWhatIsNot) {
  const AxisValues values = {{"views", "32"}, {"d_max", "1.5"}, {"scene", "cornell"}, {"bad", "x1"}};
  EXPECT_EQ(axis_uint(values, "views"), 32u);
  EXPECT_EQ(axis_real(values, "d_max"), 1.5);
  EXPECT_EQ(axis_text(values, "scene"), "cornell");
  EXPECT_EQ(axis_real(values, "absent"), std::nullopt);
  EXPECT_THROW(axis_real(values, "bad"), std::logic_error);
  EXPECT_THROW(axis_uint(values, "d_max"), std::logic_error);
}

TEST_F(Axes, AnAxisDeclaredInATestIsASweepFileKeyAndIsWrittenBack) {
  const SweepVocabulary vocabulary = current_sweep_vocabulary();
  SweepSpec spec = parse_sweep_spec(
      R"({"axes": {"passes": "test_ao", "test_gain": [1, 3], "test_ao:boost": [4]}})", "t.json", vocabulary);
  const auto combinations = sweep_combinations(spec);
  ASSERT_EQ(combinations.size(), 2u);
  EXPECT_EQ(combinations[1].at("test_gain"), 3.0);
  EXPECT_EQ(combinations[1].at("test_ao:boost"), "4");
  try {
    parse_sweep_spec(R"({"axes": {"test_gain": [0.1]}})", "t.json", vocabulary);
    FAIL() << "a gain outside [0.5, 4] was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: axes.test_gain[0]: gain 0.1"), std::string::npos) << e.what();
  }
  try {
    parse_sweep_spec(R"({"axes": {"test_ao:gain": [1]}})", "t.json", vocabulary);
    FAIL() << "an undeclared parameter was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("test_ao has no parameter \"gain\""), std::string::npos) << e.what();
  }
  // What `ldmbench view` saves: the command line and the sweep file carry the new axis.
  const RunSettings s = parsed({"--test-gain", "1,2", "--pass", "test_ao", "--param", "test_ao:boost=2"});
  const std::string line = run_command_line(s, "ldmbench", "");
  EXPECT_NE(line.find(" --test-gain 1,2 "), std::string::npos) << line;
  EXPECT_NE(line.find(" --param test_ao:boost=2"), std::string::npos) << line;
  const auto file = nlohmann::json::parse(sweep_file_json(s, ""));
  EXPECT_EQ(file["axes"]["test_gain"], nlohmann::json({1.0, 2.0}));
  EXPECT_EQ(file["axes"]["test_ao:boost"], "2");
}

TEST_F(Axes, TheRegistryListsEveryAxisWithItsDeclaration) {
  const std::vector<AxisSpec> all = registered_axes();
  auto find = [&all](const std::string& name) -> const AxisSpec* {
    for (const auto& a : all)
      if (a.qualified() == name) return &a;
    return nullptr;
  };
  for (const char* name : {"scenes", "passes", "structures", "views", "r_ldm", "d_max", "visibility",
                           "normal_offset", "trace", "ao_estimator", "sizing", "sizing_budget_mib",
                           "sizing_initial_per_pixel", "image_size", "frames", "warmup", "ppfla:k",
                           "psppfla:k", "habuffer:load_factor", "hbao:directions", "rtao:spp",
                           "indirect:r_light", "test_gain", "test_ao:boost"})
    EXPECT_NE(find(name), nullptr) << name;
  // The AO settings a pass reads through a harness axis are listed once, as that axis.
  EXPECT_EQ(find("ao:d_max"), nullptr);
  EXPECT_EQ(find("views")->display_name(), "N");
  EXPECT_EQ(find("views")->column, "n_views");
  EXPECT_TRUE(find("views")->ldm_only);
  EXPECT_FALSE(find("rtao:threads")->identity);  // how fast, not what
  const nlohmann::json j = axes_json();
  ASSERT_TRUE(j.contains("axes"));
  EXPECT_EQ(j["axes"].size(), all.size());
  EXPECT_EQ(j["axes"][0]["name"], "scenes");
  // The markdown table has a row per axis.
  const std::string md = axes_markdown();
  EXPECT_EQ(size_t(std::count(md.begin(), md.end(), '\n')), all.size() + 2);
}

// Every parameter a structure or pass reads is declared: reading an undeclared one is a
// programming error, and a --param its owner does not declare is refused naming the others.
TEST_F(Axes, ParametersAreReadAgainstTheirDeclarations) {
  for (const auto& name : structure_names()) EXPECT_NO_THROW(make_structure(name, StructureParams())) << name;
  for (const auto& name : pass_names()) EXPECT_NO_THROW(make_pass(name, StructureParams())) << name;
  try {
    make_structure("habuffer", StructureParams({{"load_factr", "1"}}, "--param habuffer"));
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("structure habuffer has no parameter 'load_factr' (its parameters: "
                                         "load_factor, max_age, key_bits)"),
              std::string::npos)
        << e.what();
  }
  // An AO setting is an axis of every pass that reads it, never a --param of one of them.
  RunSettings s;
  s.structure_params["ao"]["d_max"] = "2";
  try {
    expand_configurations(s);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("set it with --d-max"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ldm
