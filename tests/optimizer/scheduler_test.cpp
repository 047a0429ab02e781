#include "optimizer/scheduler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "optimizer/task_codec.h"

namespace fibrenet::optimizer {
namespace {

EvaluationResult SumOf(const Design& design, const Fidelity& fidelity, std::uint64_t seed) {
  EvaluationResult r;
  double sum = 0.0;
  for (const auto& [k, v] : design) sum += v;
  r.metrics["sum"] = sum + static_cast<double>(seed) + fidelity.overrides.size();
  r.units["sum"] = "m";
  return r;
}

TEST(ExecuteTask, TimesAndPassesThrough) {
  const TaskResult t = ExecuteTask(&SumOf, {{{"a", 1.0}, {"b", 2.0}}, {}, 4}, 7);
  EXPECT_EQ(t.index, 7u);
  EXPECT_TRUE(t.result.ok);
  EXPECT_DOUBLE_EQ(t.result.metrics.at("sum"), 7.0);
  EXPECT_GE(t.wall_s, 0.0);
}

TEST(ExecuteTask, FailuresBecomeReasons) {
  auto run_error = [](const Design&, const Fidelity&, std::uint64_t) -> EvaluationResult {
    throw RunError("unstable: kinetic energy jump");
  };
  TaskResult t = ExecuteTask(run_error, {}, 0);
  EXPECT_FALSE(t.result.ok);
  EXPECT_EQ(t.result.reason, "unstable: kinetic energy jump");

  auto nan = [](const Design&, const Fidelity&, std::uint64_t) {
    EvaluationResult r;
    r.metrics["m"] = std::nan("");
    return r;
  };
  t = ExecuteTask(nan, {}, 0);
  EXPECT_FALSE(t.result.ok);
  EXPECT_NE(t.result.reason.find("'m' is not finite"), std::string::npos);

  auto empty = [](const Design&, const Fidelity&, std::uint64_t) { return EvaluationResult{}; };
  EXPECT_FALSE(ExecuteTask(empty, {}, 0).result.ok);

  auto silent = [](const Design&, const Fidelity&, std::uint64_t) {
    EvaluationResult r;
    r.ok = false;
    return r;
  };
  EXPECT_FALSE(ExecuteTask(silent, {}, 0).result.reason.empty());

  auto input = [](const Design&, const Fidelity&, std::uint64_t) -> EvaluationResult {
    throw InputError("unknown scene key");
  };
  EXPECT_THROW(ExecuteTask(input, {}, 0), InputError);
}

TEST(SerialScheduler, RunsInOrderAndStops) {
  const auto scheduler = MakeSerialScheduler(&SumOf);
  EXPECT_TRUE(scheduler->is_driver());
  EXPECT_EQ(scheduler->evaluators(), 1);
  std::vector<Task> tasks;
  for (int i = 0; i < 5; ++i) tasks.push_back({{{"x", double(i)}}, {}, 0});
  std::vector<std::size_t> started, finished;
  BatchCallbacks callbacks;
  callbacks.on_start = [&](std::size_t i) { started.push_back(i); };
  callbacks.on_finish = [&](TaskResult&& r) {
    finished.push_back(r.index);
    EXPECT_DOUBLE_EQ(r.result.metrics.at("sum"), double(r.index));
  };
  callbacks.stop_requested = [&] { return started.size() >= 3; };
  scheduler->Run(tasks, callbacks);
  EXPECT_EQ(started, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(finished, started);
}

TEST(MakeScheduler, IsSerialOutsideMpirun) {
  const auto scheduler = MakeScheduler(&SumOf);
  EXPECT_TRUE(scheduler->is_driver());
  EXPECT_EQ(scheduler->description(), "serial");
}

TEST(ThreadsPerEvaluatingRank, SharesTheNodesCoresAmongItsEvaluators) {
  // Unbound ranks see every core: 2 evaluators on 2 cores get one thread each, one gets both.
  EXPECT_EQ(ThreadsPerEvaluatingRank(2, 2, 2), 1);
  EXPECT_EQ(ThreadsPerEvaluatingRank(2, 2, 1), 2);
  EXPECT_EQ(ThreadsPerEvaluatingRank(32, 32, 7), 4);
  // A rank bound to its own cores keeps them (mpirun --map-by ...:pe=4).
  EXPECT_EQ(ThreadsPerEvaluatingRank(4, 32, 8), 4);
  EXPECT_EQ(ThreadsPerEvaluatingRank(1, 16, 2), 1);
  // More evaluators than cores (oversubscribed), or none counted: still one thread.
  EXPECT_EQ(ThreadsPerEvaluatingRank(2, 2, 5), 1);
  EXPECT_EQ(ThreadsPerEvaluatingRank(2, 2, 0), 2);
}

TEST(TaskCodec, RoundTripsExactly) {
  Task task;
  task.design = {{"fibres.length_mm", 0.1 + 0.2}, {"pressing.target_thickness_um", 1e-300}};
  task.fidelity.name = "coarse";
  task.fidelity.overrides = {{"fibres.particles_per_fibre", 8}};
  task.fidelity.replicates = 3;
  task.seed = 0x7FFFFFFFFFFFFFFFULL;
  std::size_t index = 0;
  const Task back = DecodeTask(EncodeTask(task, 42), &index);
  EXPECT_EQ(index, 42u);
  EXPECT_EQ(back.design, task.design);
  EXPECT_EQ(back.fidelity.name, "coarse");
  EXPECT_EQ(back.fidelity.overrides, task.fidelity.overrides);
  EXPECT_EQ(back.fidelity.replicates, 3);
  EXPECT_EQ(back.seed, task.seed);

  WorkerReply reply;
  reply.result.index = 3;
  reply.result.wall_s = 1.25;
  reply.result.result.metrics = {{"m", 1.0 / 3.0}};
  reply.result.result.units = {{"m", "N/m"}};
  reply.result.result.artifacts = {{"snapshot", "runs/c3.h5"}};
  const WorkerReply r = DecodeReply(EncodeReply(reply));
  EXPECT_EQ(r.result.index, 3u);
  EXPECT_EQ(r.result.result.metrics, reply.result.result.metrics);
  EXPECT_EQ(r.result.result.units, reply.result.result.units);
  EXPECT_EQ(r.result.result.artifacts[0].path, "runs/c3.h5");
  EXPECT_FALSE(r.fatal);
  EXPECT_THROW(DecodeReply("{"), Error);
  EXPECT_THROW(DecodeTask("{}", &index), Error);
}

}  // namespace
}  // namespace fibrenet::optimizer
