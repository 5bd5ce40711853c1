#include "parallel.hpp"

#include <mpi.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <queue>
#include <utility>

namespace lagremap::parallel {
namespace {
int serial_scopes = 0;  // SerialScope objects alive
long reductions = 0;    // collective reductions across more than one rank

bool active() {
  if (serial_scopes > 0) return false;
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}
}  // namespace

SerialScope::SerialScope() {
  ++serial_scopes;
}
SerialScope::~SerialScope() {
  --serial_scopes;
}

int rank() {
  int r = 0;
  if (active()) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int size() {
  int n = 1;
  if (active()) MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

long reductionCount() {
  return reductions;
}

void sum(double* values, int n) {
  if (size() == 1) return;
  ++reductions;
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

void sum(std::int64_t* values, int n) {
  if (size() == 1) return;
  ++reductions;
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
}

void sum(std::uint64_t* values, int n) {
  if (size() == 1) return;
  ++reductions;
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
}

double sum(double value) {
  sum(&value, 1);
  return value;
}

double min(double value) {
  if (size() == 1) return value;
  ++reductions;
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return value;
}

double max(double value) {
  if (size() == 1) return value;
  ++reductions;
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return value;
}

StepLimit minLoc(StepLimit limit) {
  if (size() == 1) return limit;
  ++reductions;
  struct {
    double val;
    int loc;
  } pair{limit.val, limit.loc};
  MPI_Allreduce(MPI_IN_PLACE, &pair, 1, MPI_DOUBLE_INT, MPI_MINLOC, MPI_COMM_WORLD);
  limit.val = pair.val;
  limit.loc = pair.loc;
  return limit;
}

bool any(bool condition) {
  if (size() == 1) return condition;
  ++reductions;
  int flag = condition ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &flag, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return flag != 0;
}

std::string broadcast(const std::string& text) {
  if (size() == 1) return text;
  int length = int(text.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string out = text;
  out.resize(std::size_t(length));
  MPI_Bcast(out.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return out;
}

std::string firstMessage(const std::string& message) {
  const int n_ranks = size();
  if (n_ranks == 1) return message;
  int first = message.empty() ? n_ranks : rank();
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == n_ranks) return "";
  int length = int(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  std::string out = message;
  out.resize(std::size_t(length));
  MPI_Bcast(out.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  return out;
}

Spread spread(double value) {
  return {min(value), sum(value) / size(), max(value)};
}

void barrier() {
  if (size() > 1) MPI_Barrier(MPI_COMM_WORLD);
}

std::vector<KeyedValue> deliver(const std::vector<KeyedValue>& items, const std::vector<int>& to) {
  if (size() == 1) return items;
  const int n_ranks = size();
  std::vector<int> send_counts(n_ranks, 0), recv_counts(n_ranks, 0);
  for (int rank : to) ++send_counts[rank];
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> send_displs(n_ranks + 1, 0), recv_displs(n_ranks + 1, 0);
  for (int r = 0; r < n_ranks; ++r) {
    send_displs[r + 1] = send_displs[r] + send_counts[r];
    recv_displs[r + 1] = recv_displs[r] + recv_counts[r];
  }
  const auto n_received = std::size_t(recv_displs[n_ranks]);
  std::vector<long> keys(items.size()), received_keys(n_received);
  std::vector<double> values(items.size()), received_values(received_keys.size());
  std::vector<int> fill(send_displs.begin(), send_displs.end() - 1);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const int at = fill[to[i]]++;
    keys[std::size_t(at)] = items[i].key;
    values[std::size_t(at)] = items[i].value;
  }
  MPI_Alltoallv(keys.data(), send_counts.data(), send_displs.data(), MPI_LONG, received_keys.data(),
                recv_counts.data(), recv_displs.data(), MPI_LONG, MPI_COMM_WORLD);
  MPI_Alltoallv(values.data(), send_counts.data(), send_displs.data(), MPI_DOUBLE,
                received_values.data(), recv_counts.data(), recv_displs.data(), MPI_DOUBLE,
                MPI_COMM_WORLD);
  std::vector<KeyedValue> received(received_keys.size());
  for (std::size_t i = 0; i < received.size(); ++i) {
    received[i] = {received_keys[i], received_values[i]};
  }
  return received;
}

std::vector<double> gatherOnAll(const std::vector<double>& values) {
  if (size() == 1) return values;
  const int n_ranks = size(), count = int(values.size());
  std::vector<int> counts(n_ranks), displs(n_ranks + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < n_ranks; ++r) displs[r + 1] = displs[r] + counts[r];
  std::vector<double> all(static_cast<std::size_t>(displs[n_ranks]));
  MPI_Allgatherv(values.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, MPI_COMM_WORLD);
  return all;
}

void writeOnRoot(const std::string& text, std::ostream* out) {
  if (size() == 1) {
    if (out) *out << text;
    return;
  }
  if (!isRoot()) {
    const long length = long(text.size());
    MPI_Send(&length, 1, MPI_LONG, 0, 1, MPI_COMM_WORLD);
    MPI_Send(text.data(), int(length), MPI_CHAR, 0, 2, MPI_COMM_WORLD);
    return;
  }
  if (out) *out << text;
  std::string received;
  for (int r = 1; r < size(); ++r) {
    long length = 0;
    MPI_Recv(&length, 1, MPI_LONG, r, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    received.resize(std::size_t(length));
    MPI_Recv(received.data(), int(length), MPI_CHAR, r, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (out) *out << received;
  }
}

namespace {

// (tags of their own: the halo uses 0, writeOnRoot 1 and 2)
constexpr int kPieceRequestTag = 3, kPieceLengthTag = 4, kPieceTag = 5;

// A piece of lines: "key text\n" each, from lines[first] on, of about
// kMergePieceBytes (one line at least); `first` moves past them.
std::string nextPiece(const std::vector<KeyedLine>& lines, std::size_t& first) {
  std::string piece;
  while (first < lines.size() && (piece.empty() || piece.size() < kMergePieceBytes)) {
    piece += std::to_string(lines[first].key) + ' ' + lines[first].text + '\n';
    ++first;
  }
  return piece;
}

// A piece's lines back as KeyedLines, appended to `to`.
void readPiece(const std::string& piece, std::deque<KeyedLine>& to) {
  std::size_t at = 0;
  while (at < piece.size()) {
    const std::size_t space = piece.find(' ', at), end = piece.find('\n', space);
    to.push_back(
        {std::stol(piece.substr(at, space - at)), piece.substr(space + 1, end - space - 1)});
    at = end + 1;
  }
}

}  // namespace

void writeMergedOnRoot(const std::vector<KeyedLine>& lines, std::ostream* out) {
  if (size() == 1) {
    for (const KeyedLine& line : lines)
      if (out) *out << line.text << '\n';
    return;
  }
  std::size_t next = 0;
  if (!isRoot()) {  // serve rank 0's requests until the lines run out
    for (bool done = false; !done;) {
      int request = 0;
      MPI_Recv(&request, 1, MPI_INT, 0, kPieceRequestTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const std::string piece = nextPiece(lines, next);
      const long length = long(piece.size());
      MPI_Send(&length, 1, MPI_LONG, 0, kPieceLengthTag, MPI_COMM_WORLD);
      if (length > 0) {
        MPI_Send(piece.data(), int(length), MPI_CHAR, 0, kPieceTag, MPI_COMM_WORLD);
      }
      done = length == 0;
    }
    return;
  }
  // Rank 0: each rank's pending lines; a rank with none left is asked for
  // its next piece, and is done when that piece is empty.
  const int n_ranks = size();
  std::vector<std::deque<KeyedLine>> pending(n_ranks);
  std::vector<bool> done(n_ranks, false);
  const auto refill = [&](int rank) {
    if (rank == 0) {
      readPiece(nextPiece(lines, next), pending[0]);
    } else {
      const int request = 1;
      long length = 0;
      MPI_Send(&request, 1, MPI_INT, rank, kPieceRequestTag, MPI_COMM_WORLD);
      MPI_Recv(&length, 1, MPI_LONG, rank, kPieceLengthTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      std::string piece(std::size_t(length), '\0');
      if (length > 0) {
        MPI_Recv(piece.data(), int(length), MPI_CHAR, rank, kPieceTag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
      }
      readPiece(piece, pending[rank]);
    }
    done[rank] = pending[rank].empty();
  };
  using Head = std::pair<long, int>;  // a rank's next key, and the rank
  std::priority_queue<Head, std::vector<Head>, std::greater<Head>> heads;
  for (int rank = 0; rank < n_ranks; ++rank) {
    refill(rank);
    if (!done[rank]) heads.push({pending[rank].front().key, rank});
  }
  while (!heads.empty()) {
    const int rank = heads.top().second;
    heads.pop();
    if (out) *out << pending[rank].front().text << '\n';
    pending[rank].pop_front();
    if (pending[rank].empty()) refill(rank);
    if (!done[rank]) heads.push({pending[rank].front().key, rank});
  }
}

int ranksOnThisMachine() {
  if (size() == 1) return 1;
  MPI_Comm machine;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
  int ranks = 1;
  MPI_Comm_size(machine, &ranks);
  MPI_Comm_free(&machine);
  return ranks;
}

Session::Session(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
}

Session::~Session() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (initialized && !finalized) MPI_Finalize();
}

}  // namespace lagremap::parallel
