#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "core/util/atomic_file.h"
#include "core/util/fnv1a.h"
#include "core/util/json_text.h"
#include "core/util/progress.h"
#include "model/inference.h"
#include "nn/checkpoint.h"
#include "train/batch_share.h"
#include "train/junction_handoff.h"
#include "train/stage_loop.h"
#include "train/stages.h"

namespace lc2wf {

namespace fs = std::filesystem;

// Version 4: each candidate's regressed offset is kept (edge.max_offset_m needs it). Version 3: the
// manifest names the clouds it was predicted from (their fingerprint). Version 2: raw candidates; the edge
// stage selects and refines them as inference does (version 1 stored refined candidates).
constexpr int kHandoffVersion = 4;

namespace {

// One fingerprint of every cloud the hand-off predicts from, in order: regenerated clouds (another
// machine renders slightly different images) make the predicted junctions stale.
std::string clouds_fingerprint(const std::vector<const LineCloud*>& clouds) {
  std::string all;
  for (const LineCloud* c : clouds) all += std::to_string(segments_fingerprint(*c)) + ",";
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(all)));
  return hex;
}

// True when `file` (the manifest or the progress file) names this junction checkpoint step, these
// clouds and this version.
bool made_by(const fs::path& file, int64_t step, const std::string& fingerprint, bool need_offsets,
             const JunctionSelectionOptions& selection) {
  if (!fs::exists(file)) return false;
  std::ifstream in(file);
  const nlohmann::json m = nlohmann::json::parse(in, nullptr, false);
  return !m.is_discarded() && m.is_object() && m.value("junction_step", int64_t{-1}) == step &&
         m.value("clouds_fingerprint", std::string()) == fingerprint && m.value("sampling_passes", 1) == selection.sampling_passes &&
         m.value("test_time_views", 1) == selection.test_time_views &&
         m.value("density_seeds", std::string("release")) == selection.density_seeds.str() &&
         handoff_version_usable(m.value("version", 0), need_offsets);
}

}  // namespace

bool handoff_version_usable(int version, bool need_offsets) {
  return version == kHandoffVersion || (version == 3 && !need_offsets);
}

fs::path write_junction_handoff(const BuildingSet& train, const BuildingSet& val, RunLog& log, const StageRun& run,
                                const JunctionSelectionOptions& selection) {
  const bool need_offsets = std::isfinite(selection.max_offset_m);
  const nlohmann::json sampling = {{"sampling_passes", selection.sampling_passes},
                                   {"test_time_views", selection.test_time_views},
                                   {"density_seeds", selection.density_seeds.str()}};
  const fs::path dir = run.out / "predicted_junctions", manifest = dir / "manifest.json";
  // Written before the first prediction, removed with the manifest's arrival: an interrupted hand-off resumes.
  const fs::path progress = dir / "in_progress.json";
  const fs::path weights = best_checkpoint_path(run.out, "junction");
  if (!fs::exists(weights)) throw std::runtime_error(weights.string() + ": no junction model yet (run --stage junction first)");
  const int64_t step = read_checkpoint_info(weights).position.step;

  std::vector<const LineCloud*> clouds;
  for (const BuildingSet* set : {&train, &val})
    for (const LineCloud& c : set->clouds) clouds.push_back(&c);
  const std::string fingerprint = clouds_fingerprint(clouds);

  // Rank 0 decides (and clears the old manifest) for all ranks; each rank then predicts its share.
  Communicator& comm = run.communicator();
  const bool writer = comm.rank() == 0;
  std::string decision = "redo";
  if (writer && run.resume) {
    bool complete = made_by(manifest, step, fingerprint, need_offsets, selection);
    for (const LineCloud* c : clouds) complete = complete && fs::exists(predicted_junctions_path(dir, c->name));
    if (complete) decision = "keep";
    // An interrupted hand-off of the same weights: its files are whole (atomic writes), keep them.
    else if (made_by(progress, step, fingerprint, true, selection)) decision = "continue";
  }
  comm.broadcast(decision, "hand-off decision");
  if (decision == "keep") {
    if (!run.quiet) std::fprintf(stderr, "handoff: predicted junctions in %s are up to date\n", dir.string().c_str());
    return dir;
  }
  if (writer) {
    fs::remove(manifest);
    log.rewind("handoff", 0, stage_order());
    if (decision == "redo") {
      nlohmann::json p = {{"format", "lc2wf-predicted-junctions-progress"}, {"junction_step", step},
                          {"clouds_fingerprint", fingerprint}, {"version", kHandoffVersion}};
      p.update(sampling);
      write_text_atomically(progress, json_text(p, 2) + "\n");
    }
  }
  comm.barrier("hand-off progress");  // the progress file exists before any rank writes a prediction

  std::unique_ptr<JunctionNet> net = load_junction_net(weights);
  const BatchShare share = batch_share(static_cast<int64_t>(clouds.size()), comm.rank(), comm.size());
  std::unique_ptr<Progress> bar;
  if (!run.quiet) bar = std::make_unique<Progress>("predicting junctions", share.count);
  const auto t0 = std::chrono::steady_clock::now();
  int64_t kept = 0;
  for (int64_t k = share.first; k < share.first + share.count; ++k) {
    const LineCloud* c = clouds[static_cast<size_t>(k)];
    if (decision == "continue" && fs::exists(predicted_junctions_path(dir, c->name))) {
      ++kept;  // predicted before the interruption, by the same weights: inference is deterministic
    } else {
      write_predicted_junctions(dir, c->name, predict_junction_candidates(*net, *c, selection));
    }
    if (bar) bar->step();
  }
  if (bar) bar->finish();
  comm.barrier("hand-off");  // every rank's files are written before the manifest says so
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (writer) {
    nlohmann::json names = nlohmann::json::array();
    for (const LineCloud* c : clouds) names.push_back(c->name);
    nlohmann::json m = {{"format", "lc2wf-predicted-junctions-manifest"},
                        {"junction_checkpoint", weights.string()},
                        {"junction_step", step},
                        {"clouds_fingerprint", fingerprint},
                        {"version", kHandoffVersion}};
    m.update(sampling);
    m["buildings"] = names;
    write_text_atomically(manifest, json_text(m, 2) + "\n");
    fs::remove(progress);
    const double predicted = static_cast<double>(clouds.size()) - static_cast<double>(kept);
    nlohmann::json line = {{"stage", "handoff"}, {"type", "handoff"}, {"step", 0}, {"buildings", clouds.size()},
                           {"seconds", seconds}, {"buildings_per_s", seconds > 0 ? predicted / seconds : 0.0}};
    if (comm.size() == 1) line["kept_from_interrupted_run"] = kept;  // other ranks' counts stay with them
    log.append(line);
  }
  comm.barrier("hand-off manifest");  // every rank reads the manifest's identity next
  return dir;
}

nlohmann::json handoff_identity(const fs::path& dir) {
  const fs::path manifest = dir / "manifest.json";
  std::ifstream in(manifest);
  const nlohmann::json m = nlohmann::json::parse(in, nullptr, false);
  if (m.is_discarded() || !m.is_object() || !m.contains("junction_step") || !m.contains("clouds_fingerprint"))
    throw std::runtime_error(manifest.string() + ": not a complete hand-off manifest (run --stage edge without --resume)");
  nlohmann::json identity = {{"junction_step", m["junction_step"]}, {"clouds_fingerprint", m["clouds_fingerprint"]}};
  // Only when not the release's one pass, so the identities of earlier runs stay what they were.
  if (m.value("sampling_passes", 1) != 1) identity["sampling_passes"] = m["sampling_passes"];
  if (m.value("test_time_views", 1) != 1) identity["test_time_views"] = m["test_time_views"];
  if (m.value("density_seeds", std::string("release")) != "release") identity["density_seeds"] = m["density_seeds"];
  return identity;
}

}  // namespace lc2wf
