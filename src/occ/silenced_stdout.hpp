#pragma once
// OCC's readers and writers report on std::cout; the CLI's stdout is for results.
#include <iostream>
#include <sstream>

namespace mm {

// Sends std::cout to nowhere while it lives.
class SilencedStdout {
 public:
  SilencedStdout() : saved_(std::cout.rdbuf(sink_.rdbuf())) {}
  ~SilencedStdout() { std::cout.rdbuf(saved_); }
  SilencedStdout(const SilencedStdout&) = delete;
  SilencedStdout& operator=(const SilencedStdout&) = delete;

 private:
  std::ostringstream sink_;
  std::streambuf* saved_;
};

}  // namespace mm
