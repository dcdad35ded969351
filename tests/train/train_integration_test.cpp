// End to end on generated data with a tiny config: lc2wf-train (both stages and the hand-off) writes
// checkpoints and a log whose loss goes down; a run killed with SIGKILL and resumed logs exactly the
// losses of an uninterrupted run; lc2wf-infer and lc2wf-eval --weights produce files that parse; and
// inference survives degenerate clouds.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/formats/line3dpp_io.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/splits/splits.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "model/post_process_options.h"
#include "nn/model_checkpoint.h"
#include "infer/prediction_io.h"
#include "core/util/version.h"
#include "tests/common/run_cli.h"
#include "tests/common/tiny_lpt.h"
#include "tests/train/train_log.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using testing::log_lines;
using testing::step_losses;

std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const fs::path kCommandLog = fs::temp_directory_path() / ("lc2wf_train_it_cmd_" + std::to_string(::getpid()) + ".log");

// Exit code of a command; its output is kept in kCommandLog for failure messages (command_output()).
int run(const std::string& command) {
  const int status = std::system((command + " > " + kCommandLog.string() + " 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
std::string command_output() { return read_text(kCommandLog); }

// (stage, epoch, train_loss) of every "epoch" line: a mid-epoch resume must log the same means.
std::vector<std::tuple<std::string, int64_t, double>> epoch_losses(const fs::path& log) {
  std::vector<std::tuple<std::string, int64_t, double>> out;
  for (const auto& j : log_lines(log, "epoch")) out.emplace_back(j["stage"], j["epoch"], j["train_loss"]);
  return out;
}

class TrainIntegration : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("lc2wf_train_it_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "clouds");
    // Two generated buildings: one trains, the other validates (and is the held-out inference input).
    RectBuildingSpec rect;
    LBuildingSpec l;
    const Building a = make_rect_building("rect", rect), b = make_l_building("ell", l);
    SyntheticCloudOptions options;
    options.texture_per_roof_m2 = 0.3;
    write_line_cloud(dir_ / "clouds" / "rect.lcloud", make_synthetic_line_cloud(a, 7, options));
    write_line_cloud(dir_ / "clouds" / "ell.lcloud", make_synthetic_line_cloud(b, 8, options));
    std::ofstream(dir_ / "train.txt") << "rect\nell\n";
    std::ofstream(dir_ / "val.txt") << "ell\n";

    const testing::TinyLpt tiny = testing::tiny_lpt();
    const nlohmann::json &junction_lpt = tiny.junction, &edge_lpt = tiny.edge;
    // A seed whose tiny model draws a wireframe with a non-zero sAP for the validation building (half the
    // seeds tried draw an empty one after 30 edge epochs), so the one-rule check below compares real scores.
    config_ = {{"seed", 15},
               {"threads", 2},
               {"data", {{"format", "lc2wf"}, {"dir", (dir_ / "clouds").string()},
                         {"train_split", (dir_ / "train.txt").string()}, {"val_split", (dir_ / "val.txt").string()}}},
               {"junction", {{"net", {{"lpt", junction_lpt}, {"head", {{"dims", {16}}}}}},
                             {"optim", {{"lr", 3e-3}, {"milestones", {100}}}},
                             {"epochs", 40}, {"batch_size", 1}, {"val_every", 20}, {"checkpoint_every_steps", 1}}},
               {"edge", {{"net", {{"lpt", edge_lpt}, {"head", {{"dims", {16}}}}}},
                         {"optim", {{"lr", 3e-3}, {"milestones", {100}}}}, {"max_static_pairs", 16}, {"top_k", 12},
                         {"epochs", 30}, {"batch_size", 2}, {"val_every", 15}, {"checkpoint_every_steps", 1}}}};
    std::ofstream(dir_ / "tiny.json") << config_.dump(2);
  }
  static void TearDownTestSuite() {
    fs::remove_all(dir_);
    fs::remove(kCommandLog);
  }

  static std::string train_cmd(const fs::path& out, const std::string& config = "tiny.json") {
    return std::string(LC2WF_TRAIN_BIN) + " " + quote(dir_ / config) + " --quiet --out " + quote(out);
  }

  static fs::path dir_;
  static nlohmann::json config_;
};
fs::path TrainIntegration::dir_;
nlohmann::json TrainIntegration::config_;

TEST_F(TrainIntegration, TrainsKillResumesInfersAndEvaluates) {
  const fs::path straight = dir_ / "straight";
  ASSERT_EQ(run(train_cmd(straight)), 0) << command_output();
  for (const char* f : {"junction.safetensors", "edge.safetensors", "checkpoints/junction_last_0.safetensors", "checkpoints/junction_last_1.safetensors",
                        "checkpoints/junction_last_0.optim.safetensors", "checkpoints/edge_last_0.safetensors",
                        "predicted_junctions/ell.json", "predicted_junctions/rect.json", "predicted_junctions/manifest.json",
                        "config.json", "log.jsonl", "README.md"})
    EXPECT_TRUE(fs::exists(straight / f)) << f;
  // The model card says which lc2wf trained the weights and what was kept.
  std::ifstream card_file(straight / "README.md");
  const std::string card((std::istreambuf_iterator<char>(card_file)), std::istreambuf_iterator<char>());
  EXPECT_THAT(card, HasSubstr(std::string("commit ") + lc2wf_git_commit()));
  EXPECT_THAT(card, HasSubstr("| junction | `junction.safetensors` |"));
  EXPECT_THAT(card, HasSubstr("| edge | `edge.safetensors` |"));

  // The loss goes down in both stages (mean of the first vs the last epoch).
  const auto epochs = log_lines(straight / "log.jsonl", "epoch");
  for (const std::string stage : {"junction", "edge"}) {
    std::vector<double> losses;
    for (const auto& e : epochs)
      if (e["stage"] == stage) {
        losses.push_back(e["train_loss"]);
        EXPECT_EQ(e.value("precision", ""), "fp32") << stage;  // what the products ran in, for the model card
      }
    ASSERT_GE(losses.size(), 6u) << stage;
    EXPECT_LT(losses.back(), losses.front()) << stage;
  }
  EXPECT_EQ(log_lines(straight / "log.jsonl", "val").size(), 2u + 2u);  // every 20 / 15 epochs
  const auto straight_losses = step_losses(straight / "log.jsonl");
  ASSERT_EQ(straight_losses.size(), 80u + 30u);

  // An interrupted hand-off resumes: files already predicted by the same junction weights are kept, the
  // missing ones are predicted, and the result equals the uninterrupted hand-off.
  const fs::path partial = dir_ / "partial";
  fs::copy(straight, partial, fs::copy_options::recursive);
  const fs::path pj = partial / "predicted_junctions";
  const nlohmann::json manifest = nlohmann::json::parse(read_text(pj / "manifest.json"));
  fs::remove(pj / "manifest.json");
  fs::remove(pj / "rect.json");
  std::ofstream(pj / "in_progress.json") << nlohmann::json{{"junction_step", manifest["junction_step"]},
                                                           {"clouds_fingerprint", manifest["clouds_fingerprint"]},
                                                           {"version", manifest["version"]},
                                                           {"density_seeds", manifest["density_seeds"]}}.dump();
  const auto old_time = fs::last_write_time(pj / "ell.json") - std::chrono::hours(1);
  fs::last_write_time(pj / "ell.json", old_time);
  ASSERT_EQ(run(train_cmd(partial) + " --stage edge --resume"), 0) << command_output();
  EXPECT_EQ(fs::last_write_time(pj / "ell.json"), old_time) << "a prediction of the interrupted hand-off was redone";
  EXPECT_EQ(read_text(pj / "rect.json"), read_text(straight / "predicted_junctions" / "rect.json"));
  EXPECT_TRUE(fs::exists(pj / "manifest.json"));
  EXPECT_FALSE(fs::exists(pj / "in_progress.json"));
  const auto handoff = log_lines(partial / "log.jsonl", "handoff");
  ASSERT_FALSE(handoff.empty());
  EXPECT_EQ(handoff.back()["kept_from_interrupted_run"], 2);  // ell: a training and the validation building
  // Without the progress file the files cannot be trusted: everything is predicted again.
  fs::remove(pj / "manifest.json");
  ASSERT_EQ(run(train_cmd(partial) + " --stage edge --resume"), 0) << command_output();
  EXPECT_NE(fs::last_write_time(pj / "ell.json"), old_time);
  EXPECT_EQ(log_lines(partial / "log.jsonl", "handoff").back()["kept_from_interrupted_run"], 0);

  // Regenerated clouds (another machine renders slightly different images): the hand-off no longer
  // belongs to them, so it is predicted again, and the edge stage starts again instead of resuming a
  // checkpoint trained on the old junctions. Here one segment of one cloud moved by 1 mm.
  const fs::path regenerated = dir_ / "regenerated";
  fs::copy(straight, regenerated, fs::copy_options::recursive);
  fs::create_directories(dir_ / "clouds-regenerated");
  fs::copy(dir_ / "clouds" / "ell.lcloud", dir_ / "clouds-regenerated" / "ell.lcloud");
  LineCloud moved = read_line_cloud(dir_ / "clouds" / "rect.lcloud");
  moved.segments.at(0).a.x() += 1e-3;
  write_line_cloud(dir_ / "clouds-regenerated" / "rect.lcloud", moved);
  nlohmann::json regenerated_config = config_;
  regenerated_config["data"]["dir"] = (dir_ / "clouds-regenerated").string();
  regenerated_config["edge"]["epochs"] = 2;  // resumed, the old state (30 epochs) would run no step at all
  std::ofstream(dir_ / "regenerated.json") << regenerated_config.dump(2);
  ASSERT_EQ(run(train_cmd(regenerated, "regenerated.json") + " --stage edge --resume"), 0) << command_output();
  EXPECT_THAT(command_output(), HasSubstr("trained on other inputs"));
  const nlohmann::json new_manifest = nlohmann::json::parse(read_text(regenerated / "predicted_junctions" / "manifest.json"));
  EXPECT_EQ(new_manifest["junction_step"], manifest["junction_step"]);
  EXPECT_NE(new_manifest["clouds_fingerprint"], manifest["clouds_fingerprint"]);
  size_t edge_steps = 0;
  for (const auto& j : step_losses(regenerated / "log.jsonl")) edge_steps += std::get<0>(j) == "edge";
  EXPECT_EQ(edge_steps, 2u) << "the edge stage did not start again on the new hand-off";
  EXPECT_EQ(log_lines(regenerated / "log.jsonl", "handoff").size(), 1u);

  // Another value of a hand-off key: the hand-off is predicted again (the manifest records the value) and
  // the edge stage starts again on it.
  auto edge_again_with = [&](const std::string& name, const std::string& key, const nlohmann::json& value) {
    const fs::path out = dir_ / name;
    fs::copy(straight, out, fs::copy_options::recursive);
    nlohmann::json changed = config_;
    changed["edge"][key] = value;
    changed["edge"]["epochs"] = 2;
    std::ofstream(dir_ / (name + ".json")) << changed.dump(2);
    EXPECT_EQ(run(train_cmd(out, name + ".json") + " --stage edge --resume"), 0) << command_output();
    EXPECT_THAT(command_output(), HasSubstr("trained on other inputs")) << key;
    EXPECT_EQ(nlohmann::json::parse(read_text(out / "predicted_junctions" / "manifest.json"))[key], value);
    return nlohmann::json::parse(read_text(out / "predicted_junctions" / "rect.json"));
  };
  const nlohmann::json straight_candidates = nlohmann::json::parse(read_text(straight / "predicted_junctions" / "rect.json"));
  // Two sampling passes: twice the candidates.
  EXPECT_EQ(edge_again_with("two-passes", "sampling_passes", 2)["positions"].size(),
            2 * straight_candidates["positions"].size());
  // Two test-time views: as many candidates, other confidences.
  const nlohmann::json two_views = edge_again_with("two-views", "test_time_views", 2);
  EXPECT_EQ(two_views["positions"].size(), straight_candidates["positions"].size());
  EXPECT_NE(two_views["confidences"], straight_candidates["confidences"]);
  // The release's density seeds: a hand-off of its own (this small cloud's sample is every endpoint either way).
  EXPECT_EQ(edge_again_with("release-seeds", "density_seeds", "release")["positions"].size(),
            straight_candidates["positions"].size());

  // Kill -9 part-way through each stage (every step writes a checkpoint), resume until the end, and
  // compare every step loss with the uninterrupted run.
  const fs::path resumed = dir_ / "resumed";
  auto kill_when = [&](const std::string& stage, size_t steps, bool resume) {
    const pid_t pid = fork();
    if (pid == 0) {
      execl(LC2WF_TRAIN_BIN, LC2WF_TRAIN_BIN, (dir_ / "tiny.json").c_str(), "--quiet", "--out", resumed.c_str(),
            resume ? "--resume" : "--quiet", static_cast<char*>(nullptr));
      _exit(127);
    }
    for (int i = 0; i < 30000 && pid > 0; ++i) {
      size_t done = 0;
      if (fs::exists(resumed / "log.jsonl"))
        for (const auto& j : log_lines(resumed / "log.jsonl", "step")) done += j["stage"] == stage;
      if (done >= steps) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
        return true;
      }
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return false;
  };
  EXPECT_TRUE(kill_when("junction", 9, false)) << "training finished before it could be killed";
  EXPECT_TRUE(kill_when("edge", 3, true)) << "training finished before it could be killed";
  ASSERT_EQ(run(train_cmd(resumed) + " --resume"), 0) << command_output();
  EXPECT_EQ(step_losses(resumed / "log.jsonl"), straight_losses);
  EXPECT_EQ(epoch_losses(resumed / "log.jsonl"), epoch_losses(straight / "log.jsonl"));  // killed at an odd junction step
  // A completed run resumed again does nothing and keeps its log.
  ASSERT_EQ(run(train_cmd(resumed) + " --resume"), 0) << command_output();
  EXPECT_EQ(step_losses(resumed / "log.jsonl"), straight_losses);

  // Inference on the held-out building, with a preview.
  const fs::path pred = dir_ / "pred";
  ASSERT_EQ(run(std::string(LC2WF_INFER_BIN) + " --quiet --weights " + quote(straight) + " " +
                quote(dir_ / "clouds" / "ell.lcloud") + " -o " + quote(pred) + " --preview " + quote(dir_ / "ell.png")),
            0);
  const ScoredWireframe w = read_prediction(pred / "ell.obj");
  EXPECT_NO_THROW(w.check("ell"));
  const PredictionScores scores = parse_scores_json(read_text(pred / "ell.json"), "ell.json");
  ASSERT_TRUE(scores.edge_scores.has_value());
  EXPECT_EQ(scores.edge_scores->size(), w.wireframe.edges.size());
  const std::string png = read_text(dir_ / "ell.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");

  // "Evaluate on the split" in one command.
  const fs::path eval = dir_ / "eval";
  ASSERT_EQ(run(std::string(LC2WF_EVAL_BIN) + " --quiet --weights " + quote(straight) + " --data " +
                quote(dir_ / "clouds") + " --split " + quote(dir_ / "val.txt") + " --out " + quote(eval)),
            0);
  const nlohmann::json metrics = nlohmann::json::parse(read_text(eval / "metrics.json"));
  EXPECT_FALSE(metrics.empty());
  EXPECT_TRUE(fs::exists(eval / "predictions" / "ell.obj"));
  EXPECT_TRUE(fs::exists(eval / "metrics.md"));
  // The inference just made is timed in the report: every stage's seconds add up to the total.
  const nlohmann::json& timing = metrics.at("inference");
  EXPECT_EQ(timing["buildings"].get<int>(), static_cast<int>(metrics["buildings"].get<size_t>()));
  EXPECT_NEAR(timing["seconds_per_building"].get<double>(),
              timing["junction_seconds_per_building"].get<double>() + timing["edge_seconds_per_building"].get<double>() +
                  timing["post_seconds_per_building"].get<double>(), 1e-9);
  EXPECT_GT(timing["pairs_per_building"].get<double>(), 0.0);
  EXPECT_THAT(read_text(eval / "metrics.md"), HasSubstr("classified pairs per building"));
  // and the selection the scores depend on is recorded with them (the defaults here).
  EXPECT_EQ(timing["min_confidence"].get<double>(), PostProcessOptions{}.selection.min_confidence);
  EXPECT_EQ(timing["nms_radius_m"].get<double>(), PostProcessOptions{}.selection.nms_radius_m);
  EXPECT_EQ(timing["max_offset_m"].get<double>(), PostProcessOptions{}.selection.max_offset_m);
  EXPECT_EQ(timing["corner_radius_m"].get<double>(), PostProcessOptions{}.selection.corner.radius_m);
  EXPECT_EQ(timing["footing_radius_m"].get<double>(), PostProcessOptions{}.selection.footing.radius_m);
  // Scoring those saved predictions again in the same folder (as for --html) keeps the record.
  ASSERT_EQ(run(std::string(LC2WF_EVAL_BIN) + " --quiet --pred " + quote(eval / "predictions") + " --data " +
                quote(dir_ / "clouds") + " --split " + quote(dir_ / "val.txt") + " --out " + quote(eval)),
            0);
  EXPECT_EQ(nlohmann::json::parse(read_text(eval / "metrics.json")).at("inference"), timing);

  // The same clouds as Line3D++ maps with the GT beside them: Building3D's frame is still the cloud's (it was
  // the GT corners', a different scale, so the two rows of one building could not be compared).
  const fs::path maps = dir_ / "maps", gt = dir_ / "gt";
  fs::create_directories(maps), fs::create_directories(gt);
  for (const std::string& name : read_name_list(dir_ / "val.txt")) {
    const LineCloud c = read_line_cloud(dir_ / "clouds" / (name + ".lcloud"));
    write_line3dpp_txt(maps / (name + ".txt"), c);
    write_obj_wireframe(gt / (name + ".obj"), c.wireframe);
  }
  const fs::path as_maps = dir_ / "eval-maps";
  ASSERT_EQ(run(std::string(LC2WF_EVAL_BIN) + " --quiet --weights " + quote(straight) + " --data " + quote(maps) +
                " --format line3dpp --max-segment-length 0 --gt " + quote(gt) + " --split " + quote(dir_ / "val.txt") +
                " --out " + quote(as_maps)),
            0) << command_output();
  const nlohmann::json map_metrics = nlohmann::json::parse(read_text(as_maps / "metrics.json"));
  EXPECT_EQ(map_metrics["building3d"]["frame"], metrics["building3d"]["frame"]);
  EXPECT_NEAR(map_metrics["building3d"]["mean_frame_radius_m"].get<double>(),
              metrics["building3d"]["mean_frame_radius_m"].get<double>(), 1e-5);

  // One rule for junctions: the edge stage's validation of the weights it kept scores exactly what
  // lc2wf-eval --weights scores for the same weights and buildings.
  nlohmann::json best;
  for (const auto& v : log_lines(straight / "log.jsonl", "val"))
    if (v["stage"] == "edge" && v["best"].get<bool>()) best = v;
  ASSERT_FALSE(best.is_null());
  ASSERT_EQ(metrics["edge"].size(), best["sAP"].size());
  for (size_t k = 0; k < best["sAP"].size(); ++k) {
    EXPECT_DOUBLE_EQ(metrics["edge"][k]["ap"].get<double>(), best["sAP"][k].get<double>()) << k;
    EXPECT_DOUBLE_EQ(metrics["edge"][k]["recall"].get<double>(), best["sRecall"][k].get<double>()) << k;
  }
  EXPECT_DOUBLE_EQ(metrics["vertex_avg"]["ap"].get<double>(), best["vAP_mean"].get<double>());
  int predicted_edges = 0;
  for (const auto& b : metrics["per_building"]) predicted_edges += b["pred_edges"].get<int>();
  EXPECT_GT(predicted_edges, 0) << "empty wireframes would make this check vacuous";
  EXPECT_GT(metrics["edge_avg"]["ap"].get<double>(), 0.0) << "so would an sAP of zero";

  // Hostile clouds (regressions): outputs are named after the file stem, never the `name` inside the cloud
  // ("../escape" wrote outside -o); a point 6e8 m away no longer ends the batch; a FIFO fails alone.
  const fs::path hostile = dir_ / "hostile";
  fs::create_directories(hostile / "in");
  LineCloud named = read_line_cloud(dir_ / "clouds" / "ell.lcloud");
  named.name = "../escape";
  write_line_cloud(hostile / "in" / "named.lcloud", named);
  LineCloud far = read_line_cloud(dir_ / "clouds" / "ell.lcloud");
  far.segments.push_back({Vec3(6e8, 0, 0), Vec3(6e8 + 1, 0, 0)});
  if (!far.labels.empty()) far.labels.push_back(SegmentLabel{});
  if (!far.support.empty()) far.support.emplace_back();
  write_line_cloud(hostile / "in" / "far.lcloud", far);
  ASSERT_EQ(::mkfifo((hostile / "in" / "fifo.lcloud").c_str(), 0600), 0);
  const testing::CliResult r = testing::run_cli(std::string(LC2WF_INFER_BIN) + " --quiet --weights " + quote(straight) + " " +
                                                quote(hostile / "in" / "named.lcloud") + " " + quote(hostile / "in" / "fifo.lcloud") +
                                                " " + quote(hostile / "in" / "far.lcloud") + " -o " + quote(hostile / "out"));
  EXPECT_EQ(r.code, 1) << r.err;  // the FIFO could not be read
  EXPECT_THAT(r.err, HasSubstr("fifo.lcloud: is not a regular file")) << r.err;
  EXPECT_TRUE(fs::exists(hostile / "out" / "named.obj"));
  EXPECT_TRUE(fs::exists(hostile / "out" / "far.obj")) << r.err;
  EXPECT_FALSE(fs::exists(hostile / "escape.obj"));
  EXPECT_FALSE(fs::exists(hostile / "out" / "escape.obj"));

  // Fine-tuning (config "init_weights"): both stages start from the trained weights, so their first
  // step's loss is far below the first step from random weights; another network config is refused.
  nlohmann::json finetune = config_;
  finetune["init_weights"] = straight.string();
  finetune["junction"]["epochs"] = 1;
  finetune["edge"]["epochs"] = 1;
  std::ofstream(dir_ / "finetune.json") << finetune.dump(2);
  const std::string finetune_cmd = std::string(LC2WF_TRAIN_BIN) + " " + quote(dir_ / "finetune.json") + " --quiet --out ";
  ASSERT_EQ(run(finetune_cmd + quote(dir_ / "finetuned")), 0) << command_output();
  const auto tuned_losses = step_losses(dir_ / "finetuned" / "log.jsonl");
  ASSERT_EQ(tuned_losses.size(), 2u + 1u);
  EXPECT_LT(std::get<2>(tuned_losses[0]), 0.5 * std::get<2>(straight_losses[0]));   // junction
  EXPECT_LT(std::get<2>(tuned_losses[2]), 0.7 * std::get<2>(straight_losses[80]));  // edge (0.54 x measured)
  finetune["junction"]["net"]["head"]["dims"] = {24};
  std::ofstream(dir_ / "finetune.json") << finetune.dump(2);
  EXPECT_EQ(run(finetune_cmd + quote(dir_ / "mismatch")), 3);  // a data error (README: exit codes)
  EXPECT_NE(command_output().find("init_weights"), std::string::npos) << command_output();
  // Another patch distance is a fine-tune of the same weights onto other patches, not another network.
  finetune["junction"]["net"]["head"] = config_["junction"]["net"]["head"];
  finetune["junction"]["net"]["patch_distance"] = "segment";
  std::ofstream(dir_ / "finetune.json") << finetune.dump(2);
  ASSERT_EQ(run(finetune_cmd + quote(dir_ / "segment") + " --stage junction"), 0) << command_output();
  EXPECT_EQ(stored_net_config(dir_ / "segment" / "junction.safetensors", "junction").value("patch_distance", ""), "segment");

  // An --out that cannot be created is an error naming it, not an abort.
  const testing::CliResult e = testing::run_cli(std::string(LC2WF_EVAL_BIN) + " --quiet --weights " + quote(straight) + " --data " +
                                                quote(dir_ / "clouds") + " --split " + quote(dir_ / "val.txt") + " --out " +
                                                quote(dir_ / "tiny.json" / "eval"));
  EXPECT_EQ(e.code, 3) << e.err;
  EXPECT_THAT(e.err, HasSubstr("tiny.json")) << e.err;
}

TEST_F(TrainIntegration, RejectsABadConfigNamingTheKey) {
  nlohmann::json bad = config_;
  bad["junction"]["optim"]["lr"] = 0;
  std::ofstream(dir_ / "bad.json") << bad.dump();
  const testing::CliResult r =
      testing::run_cli(std::string(LC2WF_TRAIN_BIN) + " " + quote(dir_ / "bad.json") + " --out " + quote(dir_ / "bad"));
  const std::string output = r.out + r.err;
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(output, HasSubstr("junction.optim.lr")) << output;
  EXPECT_FALSE(fs::exists(dir_ / "bad"));  // nothing written for a bad config
}

// Regression: a batch larger than the split failed as "the training split gives no full batch (fewer
// buildings than batch_size?)", naming neither the count nor the key (found by the adversarial corpus).
TEST_F(TrainIntegration, ASplitSmallerThanTheBatchNamesTheCountAndTheKey) {
  nlohmann::json big = config_;
  big["junction"]["batch_size"] = 3;  // two training buildings
  std::ofstream(dir_ / "big_batch.json") << big.dump();
  const testing::CliResult r =
      testing::run_cli(std::string(LC2WF_TRAIN_BIN) + " " + quote(dir_ / "big_batch.json") + " --quiet --out " + quote(dir_ / "big"));
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_THAT(r.err, HasSubstr("junction stage: the training split's 2 usable building(s) give no full batch of junction.batch_size = 3"))
      << r.err;
}

// A bad cloud in the data folder is skipped and named on stderr, also with -q; training runs on the rest and
// the exit code says the run was partial.
TEST_F(TrainIntegration, ABadCloudIsSkippedNamedAndExitsOne) {
  fs::create_directories(dir_ / "with_bad");
  for (const char* name : {"rect.lcloud", "ell.lcloud"}) fs::copy_file(dir_ / "clouds" / name, dir_ / "with_bad" / name);
  std::ofstream(dir_ / "with_bad" / "junk.lcloud") << "not a line cloud";
  std::ofstream(dir_ / "train_bad.txt") << "rect\njunk\nell\n";
  nlohmann::json bad = config_;
  bad["data"]["dir"] = (dir_ / "with_bad").string();
  bad["data"]["train_split"] = (dir_ / "train_bad.txt").string();
  bad["junction"]["epochs"] = 1;
  bad["edge"]["epochs"] = 1;
  std::ofstream(dir_ / "bad_cloud.json") << bad.dump();
  const testing::CliResult r =
      testing::run_cli(std::string(LC2WF_TRAIN_BIN) + " " + quote(dir_ / "bad_cloud.json") + " --quiet --out " + quote(dir_ / "bad_cloud"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("lc2wf-train: skipped building junk: " + (dir_ / "with_bad" / "junk.lcloud").string())) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "bad_cloud" / "edge.safetensors"));
}

}  // namespace
}  // namespace lc2wf
