#include "transcript.hpp"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

namespace springlab::grading {
namespace {

constexpr std::int64_t most_items = 1 << 20;  // columns or springs in one value: far beyond tests
constexpr std::size_t flush_at = 1 << 16;     // bytes buffered before the worker writes them

void write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(0);  // the harness is gone: nothing more to say
    data += n, size -= std::size_t(n);
  }
}

}  // namespace

void Encoder::raw(const void* data, std::size_t size) {
  bytes_.append(static_cast<const char*>(data), size);
}

void Encoder::put(const std::string& x) {
  put(std::int64_t(x.size()));
  bytes_ += x;
}

void Encoder::put(const Vectors& x) {
  put(std::int64_t(x.cols()));
  raw(x.data(), sizeof(double) * std::size_t(x.size()));
}

void Encoder::put(const Eigen::VectorXd& x) {
  put(std::int64_t(x.size()));
  raw(x.data(), sizeof(double) * std::size_t(x.size()));
}

void Encoder::put(const std::vector<bool>& x) {
  put(std::int64_t(x.size()));
  for (const bool b : x)
    put(b);
}

void Encoder::put(const Spring& x) {
  put_all(x.p, x.q, std::uint8_t(x.family), x.k, x.b, x.rest_length);
}

void Encoder::put(const std::vector<Spring>& x) {
  put(std::int64_t(x.size()));
  for (const Spring& s : x)
    put(s);
}

void Encoder::put(const SpringFamilyParameters& x) {
  put_all(x.enabled, x.k, x.b, x.rest_length);
}

void Encoder::put(const VerletHistory& x) {
  put(x.has_previous);
  put(x.previous_position);
}

void TranscriptWriter::flush(bool now) {
  std::string& bytes = encoder_.bytes();
  if (!now && bytes.size() < flush_at) return;
  write_all(fd_, bytes.data(), bytes.size());
  bytes.clear();
}

void TranscriptWriter::forbidden(long number) {
  // In a signal handler: no allocation. The buffer is written as it stands, then the event.
  const std::string& bytes = encoder_.bytes();
  write_all(fd_, bytes.data(), bytes.size());
  char event[1 + sizeof(std::int64_t)];
  event[0] = char(Event::forbidden);
  const std::int64_t value = number;
  std::memcpy(event + 1, &value, sizeof value);
  write_all(fd_, event, sizeof event);
}

void TranscriptReader::read(void* data, std::size_t size) {
  while (buffer_.size() - at_ < size) {
    if (ended_) throw ReplayStopped("the code under test stopped");
    // Every 20 ms, whether the transcript flows or not.
    const auto now = std::chrono::steady_clock::now();
    if (watch_ && now - last_watch_ >= std::chrono::milliseconds(20)) {
      last_watch_ = now;
      watch_();
    }
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 20) == 0) continue;
    char chunk[1 << 16];
    const ssize_t n = ::read(fd_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ended_ = true;
      continue;
    }
    buffer_.erase(0, at_);
    at_ = 0;
    buffer_.append(chunk, std::size_t(n));
  }
  std::memcpy(data, buffer_.data() + at_, size);
  at_ += size;
}

Event TranscriptReader::event() {
  return Event(byte());
}

std::uint8_t TranscriptReader::byte() {
  std::uint8_t x = 0;
  read(&x, sizeof x);
  return x;
}

std::int64_t TranscriptReader::integer() {
  std::int64_t x = 0;
  read(&x, sizeof x);
  return x;
}

double TranscriptReader::number() {
  double x = 0;
  read(&x, sizeof x);
  return x;
}

std::string TranscriptReader::text(std::size_t longest) {
  const std::int64_t size = integer();
  if (size < 0 || std::size_t(size) > longest) throw ReplayStopped("a text of impossible length");
  std::string x(std::size_t(size), '\0');
  read(x.data(), x.size());
  return x;
}

void TranscriptReader::get(Vec2& x) {
  read(x.data(), sizeof(double) * 2);
}

void TranscriptReader::get(Vectors& x, Eigen::Index columns) {
  const std::int64_t n = integer();
  if (n < 0 || n > most_items || (columns >= 0 && n != columns))
    throw ReplayStopped("a result of " + std::to_string(n) + " columns where the test holds " +
                        std::to_string(columns));
  x.resize(2, Eigen::Index(n));
  read(x.data(), sizeof(double) * std::size_t(x.size()));
}

void TranscriptReader::get(std::vector<Spring>& x) {
  const std::int64_t n = integer();
  if (n < 0 || n > most_items) throw ReplayStopped(std::to_string(n) + " springs");
  x.resize(std::size_t(n));
  for (Spring& s : x) {
    s.p = int(integer());
    s.q = int(integer());
    s.family = SpringFamily(byte());
    s.k = number();
    s.b = number();
    s.rest_length = number();
  }
}

void TranscriptReader::get(VerletHistory& x, Eigen::Index columns) {
  x.has_previous = byte() != 0;
  get(x.previous_position, -1);
  if (x.previous_position.cols() != columns && x.previous_position.cols() != 0)
    throw ReplayStopped("a Verlet history of another size than the positions");
}

}  // namespace springlab::grading
