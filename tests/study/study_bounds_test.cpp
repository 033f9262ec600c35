// The study's judgement follows the scene (issue 31 item 8): its bounding box holds every
// body of a scene whose bodies are far apart and moves with every body's own velocity, so a
// valid scene is not called blown up; a study whose every run failed says so in its charts
// and in `invfree study`'s exit status.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/study/methods.h"
#include "app/study/run.h"
#include "app/study/study.h"
#include "app/study/study_chart.h"
#include "app/study/verdict.h"
#include "scene_io/scene_file.h"

namespace invfree {
namespace {

SceneDef parsed(const std::string& text) {
  const SceneLoad load = parse_scene_toml(text, "study_bounds.toml");
  EXPECT_TRUE(load.scene) << load.error;
  return load.scene ? *load.scene : SceneDef{};
}

// Two squares 100 m apart over a ground, as `simulate` runs them.
const char* kFarApart =
    "[gravity]\n[ground]\ny = -1.0\n"
    "[[body]]\noffset = [0.0, 0.0]\n"
    "[[body]]\noffset = [100.0, 0.0]\n";

TEST(StudyBounds, BodiesFarApartAreOneScene) {
  const SceneDef s = parsed(kFarApart);
  Simulation sim = make_simulation(s);
  RunMonitor m;
  m.start(sim, 0.4);
  std::string why;
  EXPECT_EQ(m.after_step(sim, &why), Verdict::Ok) << why;
  // Every study method's run of it: none is blown up by the box.
  RunOptions o;
  o.duration = 0.1;
  o.inversion_is_failure = false;
  for (const Method& method : study_methods()) {
    SceneDef run = s;
    if (!apply_method(method, run, false).empty()) continue;
    if (!method.implicit()) run.h /= 10.0;
    const RunResult r = run_scene(run, o);
    EXPECT_EQ(r.message.find("bounding box"), std::string::npos) << method.name << ": " << r.message;
  }
}

TEST(StudyBounds, TheBoxStillCatchesANodeFarFromEveryBody) {
  const SceneDef s = parsed(kFarApart);
  Simulation sim = make_simulation(s);
  RunMonitor m;
  m.start(sim, 0.4);
  std::string why;
  sim.x[1] += 200.0;  // 200 m above both
  EXPECT_EQ(m.after_step(sim, &why), Verdict::BlewUp);
  EXPECT_NE(why.find("bounding box"), std::string::npos) << why;
}

TEST(StudyBounds, ABodysOwnVelocityWidensTheBox) {
  // One body thrown sideways at 300 m/s without gravity: 120 m in 0.4 s, more than 10 L.
  const SceneDef s = parsed("[[body]]\nvelocity = [300.0, 0.0]\n");
  Simulation sim = make_simulation(s);
  RunMonitor m;
  m.start(sim, 0.4);
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.x[2 * i] += 100.0;
  std::string why;
  EXPECT_NE(m.after_step(sim, &why), Verdict::BlewUp) << why;
}

StudyRow row(const std::string& method, const std::string& failure) {
  StudyRow r;
  r.method = method;
  r.h = 0.01;
  r.tol = 0.01;
  r.n_seg = 4;
  r.error = NAN;
  r.failure = failure;
  r.fail_step = failure == "ok" || failure == "n/a" ? -1 : 1;
  return r;
}

TEST(StudyBounds, EveryRunFailedIsSaidInEveryPanel) {
  StudyResult result;
  result.scene.name = "far";
  result.rows = {row("lecture", "blew-up"), row("linear", "newton-failed"), row("arap", "n/a")};
  EXPECT_TRUE(every_run_failed(result));
  for (const auto& panels : {study_panels(result), sweeps_panels(result)})
    for (const ChartSpec& panel : panels) {
      EXPECT_EQ(panel.title.rfind("EVERY RUN FAILED", 0), 0u) << panel.title;
      ASSERT_FALSE(panel.notes.empty());
      EXPECT_NE(panel.notes.front().find("Every run of far failed"), std::string::npos);
    }
  result.rows.push_back(row("lecture", "ok"));
  EXPECT_FALSE(every_run_failed(result));
  for (const ChartSpec& panel : study_panels(result))
    EXPECT_EQ(panel.title.find("EVERY RUN FAILED"), std::string::npos) << panel.title;
}

}  // namespace
}  // namespace invfree
