#include "gui/sfml_messages.hpp"

#include "springlab/scene_text.hpp"

#include <SFML/System/Err.hpp>

#include <ostream>

namespace springlab::view {
namespace {

constexpr const char* unhelpful = "Setting vertical sync not supported";

}  // namespace

SfmlMessageFilter::SfmlMessageFilter() : original_(sf::err().rdbuf(this)) {}

SfmlMessageFilter::~SfmlMessageFilter() {
  pass_on_line();
  sf::err().rdbuf(original_);
}

SfmlMessageFilter::int_type SfmlMessageFilter::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  line_ += traits_type::to_char_type(c);
  if (line_.back() == '\n') pass_on_line();
  return c;
}

int SfmlMessageFilter::sync() {
  return original_->pubsync();
}

void SfmlMessageFilter::pass_on_line() {
  // SFML quotes file names as given ("Failed to save image \"...\""): escaped, so that a name
  // with ESC in it cannot command the terminal.
  if (line_.rfind(unhelpful, 0) != 0) {
    const std::string shown = printable_lines(line_);
    original_->sputn(shown.data(), std::streamsize(shown.size()));
  }
  line_.clear();
}

}  // namespace springlab::view
