#include "job/room_exchange.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace ilp {
namespace {

constexpr char kMagic[] = "ilp-rank-report-1";

void put_u64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_string(std::string& out, const std::string& s) {
  put_u64(out, s.size());
  out += s;
}
void put_double(std::string& out, double d) {
  std::uint64_t v;
  std::memcpy(&v, &d, sizeof v);
  put_u64(out, v);
}

struct Reader {
  const std::string& in;
  std::size_t at = 0;
  void need(std::size_t n) const {
    if (n > in.size() - at) throw std::runtime_error("a rank's report is truncated (" + std::to_string(in.size()) + " bytes)");
  }
  std::uint64_t u64() {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(in[at + i])) << (8 * i);
    at += 8;
    return v;
  }
  std::string string() {
    const std::uint64_t n = u64();
    need(n);
    std::string s = in.substr(at, n);
    at += n;
    return s;
  }
  double real() {
    const std::uint64_t v = u64();
    double d;
    std::memcpy(&d, &v, sizeof d);
    return d;
  }
};

}  // namespace

std::string encode_rank_report(const RankReport& report) {
  std::string out;
  put_string(out, kMagic);
  put_u64(out, report.rooms.size());
  for (const RoomOutcome& room : report.rooms) {
    put_u64(out, room.room);
    put_double(out, room.seconds);
    put_string(out, result_record_bytes(room.record));
    put_u64(out, room.files.size());
    for (const auto& [name, bytes] : room.files) {
      put_string(out, name);
      put_string(out, bytes);
    }
  }
  put_u64(out, report.failure ? 1 : 0);
  if (report.failure) {
    put_u64(out, report.failure->room);
    put_string(out, report.failure->message);
  }
  return out;
}

RankReport decode_rank_report(const std::string& bytes) {
  Reader in{bytes};
  if (in.string() != kMagic) throw std::runtime_error("a rank's report is not one (another ilp version on that rank?)");
  RankReport report;
  const std::uint64_t rooms = in.u64();
  for (std::uint64_t i = 0; i < rooms; ++i) {
    RoomOutcome room;
    room.room = in.u64();
    room.seconds = in.real();
    room.record = result_record_from_bytes(in.string());
    const std::uint64_t files = in.u64();
    for (std::uint64_t f = 0; f < files; ++f) {
      std::string name = in.string();
      room.files.emplace_back(std::move(name), in.string());
    }
    report.rooms.push_back(std::move(room));
  }
  if (in.u64() != 0) {
    RoomFailure failure;
    failure.room = in.u64();
    failure.message = in.string();
    report.failure = failure;
  }
  if (in.at != bytes.size()) throw std::runtime_error("a rank's report has trailing bytes");
  return report;
}

int room_rank(std::size_t room, int ranks) { return ranks <= 1 ? 0 : static_cast<int>(room % static_cast<std::size_t>(ranks)); }

}  // namespace ilp
