// SFML's error stream, minus one line: every window made under software GL (Xvfb, a machine
// without a GPU driver) prints "Setting vertical sync not supported", which says nothing a
// student can act on. Every other SFML message still reaches stderr, its control characters
// escaped.
#pragma once

#include <streambuf>
#include <string>

namespace springlab::view {

/// While it lives, sf::err() drops that one line and passes every other line on, escaped
/// (printable_lines).
class SfmlMessageFilter : public std::streambuf {
 public:
  SfmlMessageFilter();
  ~SfmlMessageFilter() override;
  SfmlMessageFilter(const SfmlMessageFilter&) = delete;
  SfmlMessageFilter& operator=(const SfmlMessageFilter&) = delete;

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  void pass_on_line();

  std::streambuf* original_;
  std::string line_;
};

}  // namespace springlab::view
