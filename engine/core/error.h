// The one exception family of fibrenet. Input errors (bad scene or campaign) map to
// exit code 2 at the CLI; run failures (instability, I/O) map to exit code 1.
#pragma once

#include <stdexcept>
#include <string>

namespace fibrenet {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad user input: the message names the file, the key and the accepted range.
class InputError : public Error {
 public:
  using Error::Error;
};

// A run that went wrong: instability, non-finite values, time step too large.
class RunError : public Error {
 public:
  using Error::Error;
};

}  // namespace fibrenet
