// The evaluation scheduler: runs batches of replicate evaluations (tasks), serially in this
// process or spread over Open MPI ranks. The campaign driver sees only this interface; MPI
// appears in scheduler.cpp alone.
//
// With MPI (the binary launched by mpirun with K > 1 ranks), rank 0 is the driver: it runs the
// campaign, owns the database and hands tasks to ranks 1..K-1, the workers, which evaluate them
// and send the results back. Rank 0 does not evaluate. Without mpirun (or with K = 1) the one
// process is the driver and evaluates every task itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "optimizer/evaluation.h"

namespace fibrenet::optimizer {

// One replicate evaluation.
struct Task {
  Design design;
  Fidelity fidelity;
  std::uint64_t seed = 0;
};

struct TaskResult {
  std::size_t index = 0;  // position of the task in the batch
  EvaluationResult result;
  double wall_s = 0.0;  // wall time of the evaluation [s]
};

struct BatchCallbacks {
  // Called on the driver just before task `index` is handed out (for "running" bookkeeping).
  std::function<void(std::size_t index)> on_start;
  // Called on the driver when task `index` has ended, in completion order (which, with MPI,
  // need not be the task order).
  std::function<void(TaskResult&& result)> on_finish;
  // Asked before each task is handed out; true leaves the rest of the batch unstarted.
  std::function<bool()> stop_requested;
};

class Scheduler {
 public:
  virtual ~Scheduler() = default;

  // True for the process that runs the campaign (rank 0, or the only process).
  virtual bool is_driver() const = 0;
  // Processes that evaluate tasks: 1 serially, K - 1 with K MPI ranks.
  virtual int evaluators() const = 0;
  // E.g. "serial" or "MPI, 3 ranks (2 evaluating, 1 thread each)".
  virtual std::string description() const = 0;

  // Driver only. Runs the batch and returns when every started task has ended. An exception
  // thrown by the evaluator (other than a failed evaluation, see ExecuteTask) or by a callback
  // stops the batch and is rethrown here once the tasks already out have come back.
  virtual void Run(const std::vector<Task>& tasks, const BatchCallbacks& callbacks) = 0;

  // Workers only: evaluates tasks until the driver ends.
  virtual void Serve() = 0;
};

// Runs one task: calls `evaluate`, times it, and turns a fibrenet::RunError, an ok == false
// result without a reason, an empty or non-finite metric into a failed result with a reason.
// Other exceptions (fibrenet::InputError included) propagate.
TaskResult ExecuteTask(const EvaluateFn& evaluate, const Task& task, std::size_t index);

// The serial scheduler: this process evaluates every task, in order.
std::unique_ptr<Scheduler> MakeSerialScheduler(EvaluateFn evaluate);

// OpenMP threads for an evaluating rank: the cores it may run on (its affinity mask), but no
// more than its share of its node's cores (the union of the masks of the node's ranks) split
// evenly among the node's evaluating ranks; at least one. Ranks that mpirun left unbound all
// see every core, and without this each would start a thread per core: on a node with as
// many evaluators as cores, every parallel region's barrier would wait for a descheduled
// thread. An OMP_NUM_THREADS in the environment is the user's choice and is kept.
int ThreadsPerEvaluatingRank(int own_cores, int node_cores, int evaluating_ranks_on_node);

// An MPI scheduler when this process was launched by mpirun with more than one rank (and the
// build has FIBRENET_ENABLE_MPI), else the serial one. Throws fibrenet::InputError when
// launched with several ranks by a build without MPI (each rank would run the campaign alone).
std::unique_ptr<Scheduler> MakeScheduler(EvaluateFn evaluate);

}  // namespace fibrenet::optimizer
