// Serial and Open MPI schedulers. This is the only file of fibrenet that includes mpi.h; the
// MPI half is compiled only when CMake's FIBRENET_ENABLE_MPI defines FIBRENET_WITH_MPI here.
#include "optimizer/scheduler.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <thread>

#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/core/stopwatch.h"
#include "optimizer/task_codec.h"

#if FIBRENET_WITH_MPI
#include <mpi.h>
#include <sched.h>
#endif

namespace fibrenet::optimizer {
namespace {

class SerialScheduler : public Scheduler {
 public:
  explicit SerialScheduler(EvaluateFn evaluate) : evaluate_(std::move(evaluate)) {}
  bool is_driver() const override { return true; }
  int evaluators() const override { return 1; }
  std::string description() const override { return "serial"; }

  void Run(const std::vector<Task>& tasks, const BatchCallbacks& callbacks) override {
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      if (callbacks.stop_requested && callbacks.stop_requested()) return;
      if (callbacks.on_start) callbacks.on_start(i);
      TaskResult result = ExecuteTask(evaluate_, tasks[i], i);
      if (callbacks.on_finish) callbacks.on_finish(std::move(result));
    }
  }

  void Serve() override {}

 private:
  EvaluateFn evaluate_;
};

// The number of ranks mpirun (Open MPI, or a PMI launcher) started, or 0 outside mpirun.
int LaunchedRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* value = std::getenv(name)) return std::atoi(value);
  }
  return 0;
}

#if FIBRENET_WITH_MPI

constexpr int kTaskTag = 1;
constexpr int kReplyTag = 2;
constexpr int kStopTag = 3;

void Send(const std::string& text, int destination, int tag) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, destination, tag, MPI_COMM_WORLD);
}

// Waits for a message like MPI_Probe, but sleeps between polls (up to 20 ms, far below an
// evaluation's time): Open MPI's blocking probe spins on a core, and on a node with as many
// ranks as cores the waiting driver and idle workers took that core from the evaluating ranks.
MPI_Status WaitForMessage(int source, int tag) {
  std::chrono::microseconds pause(100);
  while (true) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
    if (arrived) return status;
    std::this_thread::sleep_for(pause);
    pause = std::min(2 * pause, std::chrono::microseconds(20000));
  }
}

// Receives the message announced by `status` (after WaitForMessage).
std::string Receive(const MPI_Status& status) {
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Status received;
  MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           &received);
  return text;
}

class MpiScheduler : public Scheduler {
 public:
  explicit MpiScheduler(EvaluateFn evaluate) : evaluate_(std::move(evaluate)) {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
      owns_mpi_ = true;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    if (size_ > 1) ShareTheNodesCores();
  }

  ~MpiScheduler() override {
    // Workers wait in Serve() until told to stop. Run() never leaves tasks out, so every
    // worker is idle here.
    if (rank_ == 0) {
      for (int worker = 1; worker < size_; ++worker) Send(std::string(), worker, kStopTag);
    }
    if (owns_mpi_) MPI_Finalize();
  }

  bool is_driver() const override { return rank_ == 0; }
  int evaluators() const override { return size_ > 1 ? size_ - 1 : 1; }
  std::string description() const override {
    return fmt::format("MPI, {} ranks ({} evaluating, {} thread{} each)", size_, evaluators(),
                       threads_, threads_ == 1 ? "" : "s");
  }

  void Run(const std::vector<Task>& tasks, const BatchCallbacks& callbacks) override {
    if (size_ == 1) {
      SerialScheduler(evaluate_).Run(tasks, callbacks);
      return;
    }
    std::vector<int> idle;
    for (int worker = size_ - 1; worker >= 1; --worker) idle.push_back(worker);
    int outstanding = 0;
    std::size_t next = 0;
    bool stopping = false;
    std::exception_ptr error;
    while (true) {
      while (!stopping && next < tasks.size() && !idle.empty()) {
        try {
          if (callbacks.stop_requested && callbacks.stop_requested()) {
            stopping = true;
            break;
          }
          if (callbacks.on_start) callbacks.on_start(next);
        } catch (...) {
          error = std::current_exception();
          stopping = true;
          break;
        }
        Send(EncodeTask(tasks[next], next), idle.back(), kTaskTag);
        idle.pop_back();
        ++outstanding;
        ++next;
      }
      if (outstanding == 0) break;
      const MPI_Status status = WaitForMessage(MPI_ANY_SOURCE, kReplyTag);
      WorkerReply reply = DecodeReply(Receive(status));
      idle.push_back(status.MPI_SOURCE);
      --outstanding;
      if (error) continue;  // draining after an error: the results are dropped
      if (reply.fatal) {
        const std::string message = fmt::format("rank {}: {}", status.MPI_SOURCE, reply.message);
        error = reply.input_error ? std::make_exception_ptr(InputError(message))
                                  : std::make_exception_ptr(RunError(message));
        stopping = true;
        continue;
      }
      try {
        if (callbacks.on_finish) callbacks.on_finish(std::move(reply.result));
      } catch (...) {
        error = std::current_exception();
        stopping = true;
      }
    }
    if (error) std::rethrow_exception(error);
  }

  void Serve() override {
    if (rank_ == 0) return;
    while (true) {
      const MPI_Status status = WaitForMessage(0, MPI_ANY_TAG);
      const std::string text = Receive(status);
      if (status.MPI_TAG == kStopTag) return;
      std::size_t index = 0;
      const Task task = DecodeTask(text, &index);
      WorkerReply reply;
      reply.result.index = index;
      try {
        reply.result = ExecuteTask(evaluate_, task, index);
      } catch (const InputError& e) {
        reply.fatal = true;
        reply.input_error = true;
        reply.message = e.what();
      } catch (const std::exception& e) {
        reply.fatal = true;
        reply.message = e.what();
      }
      Send(EncodeReply(reply), 0, kReplyTag);
    }
  }

 private:
  // Sets the evaluating ranks' thread count (ThreadsPerEvaluatingRank) from the affinity
  // masks of the ranks on this node; every rank takes part. threads_ is what this node's
  // evaluators use (on the driver: what they were given, for the description).
  void ShareTheNodesCores() {
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    int node_ranks = 1;
    MPI_Comm_size(node, &node_ranks);
    cpu_set_t own;
    CPU_ZERO(&own);
    if (sched_getaffinity(0, sizeof own, &own) != 0) CPU_SET(0, &own);
    std::vector<cpu_set_t> masks(static_cast<std::size_t>(node_ranks));
    MPI_Allgather(&own, sizeof own, MPI_BYTE, masks.data(), sizeof own, MPI_BYTE, node);
    cpu_set_t node_cores;
    CPU_ZERO(&node_cores);
    for (cpu_set_t& mask : masks) CPU_OR(&node_cores, &node_cores, &mask);
    int driver_here = rank_ == 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &driver_here, 1, MPI_INT, MPI_MAX, node);
    MPI_Comm_free(&node);
    if (std::getenv("OMP_NUM_THREADS") != nullptr) {
      threads_ = ThreadCount();
      return;
    }
    threads_ = ThreadsPerEvaluatingRank(CPU_COUNT(&own), CPU_COUNT(&node_cores),
                                        node_ranks - driver_here);
    if (rank_ != 0) SetThreadCount(threads_);
  }

  EvaluateFn evaluate_;
  int threads_ = 1;
  bool owns_mpi_ = false;
  int rank_ = 0;
  int size_ = 1;
};

#endif  // FIBRENET_WITH_MPI

}  // namespace

int ThreadsPerEvaluatingRank(int own_cores, int node_cores, int evaluating_ranks_on_node) {
  const int share = node_cores / std::max(evaluating_ranks_on_node, 1);
  return std::max(1, std::min(own_cores, share));
}

TaskResult ExecuteTask(const EvaluateFn& evaluate, const Task& task, std::size_t index) {
  TaskResult out;
  out.index = index;
  const Stopwatch clock;
  try {
    out.result = evaluate(task.design, task.fidelity, task.seed);
  } catch (const RunError& e) {
    out.result = EvaluationResult{};
    out.result.ok = false;
    out.result.reason = e.what();
  }
  out.wall_s = clock.Seconds();
  EvaluationResult& r = out.result;
  if (!r.ok) {
    if (r.reason.empty()) r.reason = "evaluation failed (the evaluator gave no reason)";
    return out;
  }
  if (r.metrics.empty()) {
    r.ok = false;
    r.reason = "the evaluator returned no metrics";
  }
  for (const auto& [name, value] : r.metrics) {
    if (!std::isfinite(value)) {
      r.ok = false;
      r.reason = fmt::format("metric '{}' is not finite ({})", name, value);
      break;
    }
  }
  return out;
}

std::unique_ptr<Scheduler> MakeSerialScheduler(EvaluateFn evaluate) {
  return std::make_unique<SerialScheduler>(std::move(evaluate));
}

std::unique_ptr<Scheduler> MakeScheduler(EvaluateFn evaluate) {
  const int ranks = LaunchedRanks();
#if FIBRENET_WITH_MPI
  if (ranks > 1) return std::make_unique<MpiScheduler>(std::move(evaluate));
#else
  if (ranks > 1) {
    throw InputError(
        fmt::format("launched on {} MPI ranks, but this build has no MPI support (configure with "
                    "-DFIBRENET_ENABLE_MPI=ON); run it without mpirun",
                    ranks));
  }
#endif
  return MakeSerialScheduler(std::move(evaluate));
}

}  // namespace fibrenet::optimizer
