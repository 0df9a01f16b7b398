#include <cstdio>
#include "harness/gl/egl_context.h"
#include "harness/scene/scene_loader.h"
#include "harness/passes/ao_pass.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "harness/image/image.h"
using namespace ldm;
int main(int argc, char** argv) {
  auto ctx = HeadlessContext::create({});
  printf("%s | %s\n", ctx->device().gl_renderer.c_str(), ctx->device().gl_version.c_str());
  Scene scene = load_scene(argc > 1 ? argv[1] : "cornell");
  AttributeSet attrs; attrs.normals = true;
  GpuScene gs(scene, attrs);
  ViewSet vs = make_view_set(scene.bounding_sphere(), 32, 128);
  GpuViewSet gvs(vs);
  FragmentCensus census = take_fragment_census(gs, gvs);
  printf("fragments %llu max %u\n", (unsigned long long)census.total_fragments, census.max_depth_complexity);
  BuildInputs in{gs, gvs, census, {}};
  auto s = make_structure("psppsll", {});
  s->prepare(in);
  GpuTimer timer;
  for (int f = 0; f < 3; ++f) {
    timer.begin_frame();
    s->build(in, &timer);
    auto t = timer.end_frame();
    for (auto& [n, ms] : t) printf("%s %.3f ms  ", n.c_str(), ms);
    auto st = s->stats();
    LdmInspector insp(*s, in);
    auto integ = insp.check();
    printf("\nstored %llu lost %llu walk %llu unsorted %llu checksum %llx\n", (unsigned long long)st.fragments_stored, (unsigned long long)st.fragments_lost, (unsigned long long)integ.fragments, (unsigned long long)integ.unsorted_pixels, (unsigned long long)integ.checksum);
  }
  GBufferPass gb(256, 256);
  AoPass ao(*s, in, 256, 256, scene.ao);
  timer.begin_frame();
  gb.render(gs, scene, &timer);
  ao.render(gb, &timer);
  for (auto& [n, ms] : timer.end_frame()) printf("%s %.3f ms  ", n.c_str(), ms);
  Image img = ao.read_image();
  write_exr("/tmp/ao.exr", img); write_png("/tmp/ao.png", img);
  printf("\nok\n");
}
