// offsetopt batch MANIFEST.tsv: run `optimize` on every line of a manifest, in parallel and
// resumably, for print farms (issue 14). Each line is an independent, deterministic job, so a
// scheduler (GNU parallel, a Slurm job array, a Kubernetes Indexed Job) can run one line or one
// shard per machine with --line or --shard; nothing here distributes work between machines.
//
// Each job is a child process of this same binary (fork + exec of /proc/self/exe) running
// `optimize` in the manifest's folder with exactly the arguments a single run would get, so its
// outputs are byte-identical to a single run's, a crash or an out-of-memory kill ends only that
// job, and its stderr goes to its own log file instead of interleaving with the others.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "io/json.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"
#include "util/format_double.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt batch MANIFEST.tsv [--jobs N] [--line I | --shard I/N] [--format EXT]\n"
    "\n"
    "Runs 'offsetopt optimize' once per line of MANIFEST.tsv, N jobs at a time, each as a child\n"
    "process in the manifest's folder (relative paths are relative to it). The manifest is\n"
    "tab-separated with a header naming its columns: 'input' and 'goal' (required), 'options'\n"
    "(optimize's options as one string, split at spaces; there is no quoting, no value needs a\n"
    "space) and 'output' (the prefix of the job's files; default: the input without its\n"
    "extension, then '.' and the goal). Empty lines and lines starting with '#' are skipped.\n"
    "\n"
    "Per job: PREFIX.EXT (the printable solid), PREFIX.json (the report), PREFIX.log (the job's\n"
    "stderr) and PREFIX.key (what the outputs were made from: this build, the input's size and\n"
    "FNV-1a hash, the goal, the options and the format). A line whose key file matches and whose\n"
    "solid and report exist is skipped: rerunning a manifest only runs what is new, changed or\n"
    "failed (exit 1 or 2). At the end MANIFEST.summary.tsv and MANIFEST.summary.json (manifest name\n"
    "without .tsv; with --line I or --shard I/N: .summary.line-I / .summary.shard-I-of-N) list\n"
    "each line's status, exit code, reason and seconds.\n",
    {
        {"--jobs", "N", "1", OptionRange::integer(1, 256), "jobs run at the same time (each optimize uses --threads threads, 2 by default)", "2"},
        {"--line", "I", "every line", OptionRange::integer(1, 1000000, " and at most the number of lines"),
         "run only data line I (1 = the first line after the header), e.g. a Slurm array index", "1"},
        {"--shard", "I/N", "every line", "0 <= I < N <= 1000000",
         "run only the lines whose number L has (L - 1) mod N = I, e.g. a Kubernetes completion index", "0/2"},
        {"--format", "EXT", "obj", "obj | stl | ply | 3mf", "the solid's file format", "3mf"},
        {"--quiet", "", "off", "flag", "no per-job progress on stderr", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    "exit codes: 0 every selected line ended 0 (now or in an earlier run); otherwise the first\n"
    "of 1, 2, 3 that some line ended with (see the summary); 2 also for a bad manifest or usage.\n"};

struct Job {
  int number = 0;        // data line number, from 1
  int file_line = 0;     // line in the manifest file
  std::string input, goal, output;
  std::vector<std::string> options;
  // Filled while running.
  std::string key, status, reason;
  int exit_code = -1;
  double seconds = 0.0;
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(separator, start);
    fields.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return fields;
    start = at + 1;
  }
}


bool is_option_name(const std::string& token, const char* name) {
  for (const std::string& n : option_names(name))
    if (n == token) return true;
  return false;
}

// FNV-1a, 64 bits: a resume key, not a security hash.
std::string fnv1a64_hex(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

std::string read_small_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::string();
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Options a manifest line may not give, because batch sets them.
bool reserved_option(const std::string& token) {
  return token == "-o" || token == "--output" || token == "--report" || token == "--goal" || token == "-h" ||
         token == "--help";
}

std::vector<Job> read_manifest(const std::string& path, const std::string& text) {
  std::vector<Job> jobs;
  const std::vector<std::string> lines = split(text, '\n');
  int column_input = -1, column_goal = -1, column_options = -1, column_output = -1;
  std::size_t columns = 0;
  bool header_seen = false;
  const std::vector<OptionSpec>& known = optimize_options();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string line = lines[i];
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (i == 0 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // a UTF-8 BOM, as spreadsheets write
    const int file_line = static_cast<int>(i + 1);
    const std::string where = path + ":" + std::to_string(file_line);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = split(line, '\t');
    if (!header_seen) {
      header_seen = true;
      columns = fields.size();
      for (std::size_t c = 0; c < fields.size(); ++c) {
        int* slot = fields[c] == "input" ? &column_input : fields[c] == "goal" ? &column_goal
                  : fields[c] == "options" ? &column_options : fields[c] == "output" ? &column_output : nullptr;
        if (!slot) throw UsageError(where + ": unknown manifest column '" + fields[c] + "' (input, goal, options, output)");
        if (*slot >= 0) throw UsageError(where + ": column '" + fields[c] + "' appears twice");
        *slot = static_cast<int>(c);
      }
      if (column_input < 0 || column_goal < 0)
        throw UsageError(where + ": the header must name the columns 'input' and 'goal' (tab-separated)");
      continue;
    }
    if (fields.size() != columns)
      throw UsageError(where + ": " + std::to_string(fields.size()) + " tab-separated fields, the header has " + std::to_string(columns));
    if (jobs.size() >= 1000000) throw UsageError(where + ": more than 1000000 lines");
    Job job;
    job.number = static_cast<int>(jobs.size() + 1);
    job.file_line = file_line;
    job.input = fields[column_input];
    job.goal = fields[column_goal];
    if (job.input.empty() || job.goal.empty()) throw UsageError(where + ": empty input or goal");
    if (column_options >= 0) job.options = split_words(fields[column_options], " \t");
    for (const std::string& token : job.options) {
      if (token.size() < 2 || token[0] != '-') continue;
      if (reserved_option(token)) throw UsageError(where + ": options may not contain " + token + " (batch sets it)");
      bool found = false;
      for (const OptionSpec& o : known) found = found || is_option_name(token, o.names);
      if (!found) throw UsageError(where + ": unknown optimize option '" + token + "'");
    }
    if (column_output >= 0 && !fields[column_output].empty()) {
      job.output = fields[column_output];
    } else {
      const std::filesystem::path input(job.input);
      job.output = (input.parent_path() / input.stem()).string() + "." + job.goal;
    }
    jobs.push_back(std::move(job));
  }
  if (!header_seen) throw UsageError(path + ": empty manifest (no header line)");
  // Two lines writing the same files would overwrite each other in parallel.
  std::map<std::string, int> seen;
  for (const Job& job : jobs) {
    const std::string normal = std::filesystem::path(job.output).lexically_normal().string();
    const auto [it, inserted] = seen.emplace(normal, job.file_line);
    if (!inserted)
      throw UsageError(path + ":" + std::to_string(job.file_line) + ": output prefix '" + job.output + "' is also line " +
                       std::to_string(it->second) + "'s");
  }
  return jobs;
}

// The last "Error: ..." line of a job's log, without the prefix.
std::string reason_from_log(const std::string& log) {
  std::string reason;
  for (const std::string& line : split(log, '\n'))
    if (line.rfind("Error: ", 0) == 0) reason = line.substr(7);
  return reason;
}

// Starts one job: fork, then in the child chdir to the manifest's folder, send stdout and
// stderr to the log, and exec this binary's optimize. Returns the pid, or -1.
pid_t start_job(const std::string& self, const std::string& folder, const std::string& log,
                const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  std::vector<std::string> storage = arguments;
  for (std::string& a : storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  // Child: only async-signal-safe calls until exec.
  if (::chdir(folder.c_str()) != 0) ::_exit(127);
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) ::_exit(127);
  ::dup2(fd, 1);
  ::dup2(fd, 2);
  ::execv(self.c_str(), argv.data());
  ::_exit(127);
}

struct BatchOptions {
  std::string manifest, format = "obj";
  int jobs_at_once = 1, only_line = 0, shard_index = -1, shard_count = 0;
  bool quiet = false;
  bool help = false;
};

BatchOptions parse_batch_options(const Args& args) {
  ArgCursor cursor(args);
  BatchOptions o;
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("batch", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      o.help = true;
      return o;
    } else if (arg == "--jobs") {
      o.jobs_at_once = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--line") {
      o.only_line = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--shard") {
      const std::string& value = cursor.value_of(arg);
      const std::size_t slash = value.find('/');
      if (slash == std::string::npos) throw UsageError("--shard expects I/N, got '" + value + "'");
      o.shard_count = parse_int(value.substr(slash + 1), "--shard N", 1, 1000000);
      o.shard_index = parse_int(value.substr(0, slash), "--shard I", 0, o.shard_count - 1);
    } else if (arg == "--format") {
      o.format = cursor.value_of(arg);
      if (o.format != "obj" && o.format != "stl" && o.format != "ply" && o.format != "3mf")
        throw UsageError("--format must be obj, stl, ply or 3mf, got '" + o.format + "'");
    } else if (arg == "--quiet") {
      o.quiet = true;
    } else if (o.manifest.empty()) {
      o.manifest = arg;
    } else {
      throw UsageError("batch takes one manifest, got a second one '" + arg + "'");
    }
  }
  if (o.manifest.empty()) throw UsageError("batch needs a manifest file (try 'offsetopt batch --help')");
  if (o.only_line > 0 && o.shard_count > 0) throw UsageError("--line and --shard exclude each other");
  return o;
}

// Where the jobs run: the manifest's folder, this binary and its build.
struct BatchPlace {
  std::string folder;
  std::filesystem::path base;
  std::string self, build;
};

// Each selected job's key (what its outputs are made from); the jobs whose key file matches and
// whose outputs exist are marked skipped, the others returned to run.
std::vector<Job*> jobs_to_run(const std::vector<Job*>& selected, const BatchOptions& o, const BatchPlace& place) {
  const std::string& format = o.format;
  const bool quiet = o.quiet;
  const std::filesystem::path& base = place.base;
  const std::string& build = place.build;
  std::vector<Job*> to_run;
  for (Job* job : selected) {
    std::string bytes;
    bool readable = true;
    try {
      bytes = read_file_capped((base / job->input).string());
    } catch (const MeshInputError&) {
      readable = false;  // the job itself will say why
    }
    std::string options;
    for (const std::string& option : job->options) options += (options.empty() ? "" : " ") + option;
    if (readable)
      job->key = "offsetopt batch key 1\nbuild: " + build + "\ninput: " + job->input + "\ninput_bytes: " +
                 std::to_string(bytes.size()) + "\ninput_fnv1a64: " + fnv1a64_hex(bytes) + "\ngoal: " + job->goal +
                 "\noptions: " + options + "\nformat: " + format + "\n";
    const std::filesystem::path prefix = base / job->output;
    const std::string old_key = read_small_file(prefix.string() + ".key");
    const bool done_before = readable && !old_key.empty() && old_key.rfind(job->key, 0) == 0 &&
                             std::filesystem::exists(prefix.string() + "." + format) &&
                             std::filesystem::exists(prefix.string() + ".json");
    if (done_before) {
      job->status = "skipped";
      const std::size_t at = old_key.find("exit: ", job->key.size());
      job->exit_code = at == std::string::npos ? 0 : std::atoi(old_key.c_str() + at + 6);
      const std::size_t r = old_key.find("reason: ", job->key.size());
      if (r != std::string::npos) job->reason = old_key.substr(r + 8, old_key.find('\n', r) - r - 8);
      if (!quiet)
        std::fprintf(stderr, "[line %d] %s %s: skipped, done before with the same input and options (exit %d)\n", job->number,
                     job->input.c_str(), job->goal.c_str(), job->exit_code);
    } else {
      to_run.push_back(job);
    }
  }
  return to_run;
}

// Runs the jobs, at most o.jobs_at_once children at a time; fills each job's status, exit code,
// reason and seconds, and writes the key file of each that ended 0 or 3.
void run_jobs(const std::vector<Job*>& to_run, const BatchOptions& o, const BatchPlace& place) {
  const std::string& format = o.format;
  const bool quiet = o.quiet;
  const int jobs_at_once = o.jobs_at_once;
  const std::filesystem::path& base = place.base;
  const std::string& self = place.self;
  const std::string& folder = place.folder;
  std::map<pid_t, std::pair<Job*, std::chrono::steady_clock::time_point>> running;
  std::size_t next = 0, finished = 0;
  while (next < to_run.size() || !running.empty()) {
    while (next < to_run.size() && static_cast<int>(running.size()) < jobs_at_once) {
      Job* job = to_run[next++];
      const std::string prefix = job->output;
      std::vector<std::string> argv = {self, "optimize", job->input, "--goal", job->goal, "-o", prefix + "." + format,
                                       "--report", prefix + ".json"};
      argv.insert(argv.end(), job->options.begin(), job->options.end());
      std::error_code ignored;
      std::filesystem::remove((base / job->output).string() + ".key", ignored);  // stale until this run ends
      const std::filesystem::path log = base / (prefix + ".log");
      if (log.has_parent_path()) std::filesystem::create_directories(log.parent_path(), ignored);
      const pid_t pid = start_job(self, folder, std::filesystem::absolute(log).string(), argv);
      if (pid < 0) {
        job->status = "not started";
        job->exit_code = kExitInternal;
        job->reason = std::string("fork failed: ") + std::strerror(errno);
        ++finished;
        continue;
      }
      running[pid] = {job, std::chrono::steady_clock::now()};
      if (!quiet)
        std::fprintf(stderr, "[line %d] %s %s: started (%zu of %zu to run)\n", job->number, job->input.c_str(),
                     job->goal.c_str(), next, to_run.size());
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waitpid failed: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    Job* job = it->second.first;
    job->seconds = seconds_since(it->second.second);
    running.erase(it);
    ++finished;
    job->status = "ran";
    const std::string log = read_small_file((base / (job->output + ".log")).string());
    if (WIFEXITED(status)) {
      job->exit_code = WEXITSTATUS(status);
      job->reason = job->exit_code == 0 ? "goal met and verified" : reason_from_log(log);
      if (job->exit_code == 127 && job->reason.empty()) job->reason = "could not start (chdir, log file or exec failed)";
    } else {
      job->exit_code = 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
      job->reason = "killed by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    }
    // Exit 0 and 3 are results (the same input gives them again); 1 and 2 are retried next time.
    if ((job->exit_code == 0 || job->exit_code == kExitGoalNotMet) && !job->key.empty())
      write_text((base / (job->output + ".key")).string(),
                 job->key + "exit: " + std::to_string(job->exit_code) + "\nreason: " + job->reason + "\n");
    if (!quiet)
      std::fprintf(stderr, "[line %d] %s %s: exit %d in %.2f s%s%s (%zu of %zu done)\n", job->number, job->input.c_str(),
                   job->goal.c_str(), job->exit_code, job->seconds, job->reason.empty() ? "" : ": ",
                   job->reason.c_str(), finished, to_run.size());
  }
}

// Writes MANIFEST.summary.tsv and .json (with the --line / --shard suffix); returns the batch's
// exit code.
int write_summary(const std::vector<Job*>& selected, const BatchOptions& o, const BatchPlace& place) {
  const std::string& manifest = o.manifest;
  const std::filesystem::path manifest_path(manifest);
  const std::filesystem::path& base = place.base;
  std::string stem = manifest_path.filename().string();
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".tsv") == 0) stem.resize(stem.size() - 4);
  std::string suffix = ".summary";
  if (o.only_line > 0) suffix += ".line-" + std::to_string(o.only_line);
  if (o.shard_count > 0) suffix += ".shard-" + std::to_string(o.shard_index) + "-of-" + std::to_string(o.shard_count);
  const std::string summary_base = (base / (stem + suffix)).string();
  std::string tsv = "line\tinput\tgoal\toutput\tstatus\texit\treason\tseconds\n";
  Json rows = Json::array();
  int counts[4] = {0, 0, 0, 0};
  int ran = 0, skipped = 0, worst = kExitOk;
  const auto rank = [](int code) { return code == 0 ? 0 : code == 3 ? 1 : code == 2 ? 2 : 3; };
  for (const Job* job : selected) {
    std::string reason = job->reason;
    for (char& c : reason)
      if (c == '\t' || c == '\n') c = ' ';
    tsv += std::to_string(job->number) + "\t" + job->input + "\t" + job->goal + "\t" + job->output + "\t" + job->status +
           "\t" + std::to_string(job->exit_code) + "\t" + reason + "\t" + format_double(job->seconds) + "\n";
    Json row = Json::object();
    row["line"] = job->number;
    row["input"] = job->input;
    row["goal"] = job->goal;
    row["output"] = job->output;
    row["status"] = job->status;
    row["exit"] = job->exit_code;
    row["reason"] = job->reason;
    row["seconds"] = job->seconds;
    rows.push_back(row);
    (job->status == "skipped" ? skipped : ran) += 1;
    const int code = job->exit_code >= 0 && job->exit_code <= 3 ? job->exit_code : kExitInternal;
    counts[code] += 1;
    if (rank(code) > rank(worst)) worst = code == 1 ? kExitInternal : code;
  }
  Json summary = Json::object();
  summary["manifest"] = manifest;
  summary["lines"] = static_cast<long long>(selected.size());
  summary["ran"] = ran;
  summary["skipped"] = skipped;
  Json by_exit = Json::object();
  for (int c = 0; c < 4; ++c) by_exit[std::to_string(c)] = counts[c];
  summary["exit_counts"] = by_exit;
  summary["jobs"] = rows;
  write_text(summary_base + ".tsv", tsv, {manifest});
  write_text(summary_base + ".json", summary.dump(2) + "\n", {manifest});
  if (!o.quiet)
    std::fprintf(stderr, "batch: %zu lines, %d ran, %d skipped; exit 0: %d, 3: %d, 2: %d, 1: %d; summary %s.tsv\n",
                 selected.size(), ran, skipped, counts[0], counts[3], counts[2], counts[1], summary_base.c_str());
  return worst;
}

}  // namespace

int run_batch(const Args& args) {
  const BatchOptions o = parse_batch_options(args);
  if (o.help) {
    write_text("-", format_help(kHelp));
    return kExitOk;
  }
  std::string text;
  try {
    text = read_file_capped(o.manifest);
  } catch (const MeshInputError& e) {
    throw UsageError(e.what());
  }
  std::vector<Job> all = read_manifest(o.manifest, text);
  if (o.only_line > static_cast<int>(all.size()))
    throw UsageError("--line " + std::to_string(o.only_line) + ": " + o.manifest + " has " + std::to_string(all.size()) +
                     " lines");
  std::vector<Job*> selected;
  for (Job& job : all)
    if ((o.only_line == 0 || job.number == o.only_line) &&
        (o.shard_count == 0 || (job.number - 1) % o.shard_count == o.shard_index))
      selected.push_back(&job);

  const std::filesystem::path manifest_path(o.manifest);
  BatchPlace place;
  place.folder = manifest_path.parent_path().empty() ? "." : manifest_path.parent_path().string();
  place.base = std::filesystem::path(place.folder);
  {
    std::error_code ec;
    place.self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    if (ec || place.self.empty()) throw std::runtime_error("cannot find this program's path in /proc/self/exe");
  }
  place.build = std::string(OFFSETOPT_VERSION) + " " + OFFSETOPT_BUILD_ID;

  run_jobs(jobs_to_run(selected, o, place), o, place);
  return write_summary(selected, o, place);
}

}  // namespace offsetopt::cli
