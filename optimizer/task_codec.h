// Text encoding of tasks and results for sending between processes (the MPI scheduler).
// JSON: numbers round-trip exactly, and a worker of another build fails loudly, not silently.
#pragma once

#include <string>

#include "optimizer/scheduler.h"

namespace fibrenet::optimizer {

std::string EncodeTask(const Task& task, std::size_t index);
// Throws fibrenet::Error for malformed text.
Task DecodeTask(const std::string& text, std::size_t* index);

// A worker's answer: a result, or a fatal error that must stop the campaign.
struct WorkerReply {
  TaskResult result;
  bool fatal = false;
  bool input_error = false;  // the fatal error was bad input (exit code 2)
  std::string message;       // of the fatal error
};

std::string EncodeReply(const WorkerReply& reply);
// Throws fibrenet::Error for malformed text.
WorkerReply DecodeReply(const std::string& text);

}  // namespace fibrenet::optimizer
