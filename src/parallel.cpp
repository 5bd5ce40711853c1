#include "parallel.hpp"

#include <mpi.h>

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
