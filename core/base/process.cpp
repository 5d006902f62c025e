// run_process and the plotting interpreter: see process.hpp.
#include "core/base/process.hpp"

#include "core/base/error.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace tmlab {

std::string ProcessStatus::describe() const {
  if (!started) return "could not start: " + error;
  if (signal != 0) return "killed by signal " + std::to_string(signal);
  return "exit status " + std::to_string(exit_code);
}

ProcessStatus run_process(const std::vector<std::string>& argv, const ProcessOutput& output) {
  if (argv.empty() || argv[0].empty()) throw Error("run_process: no program given");
  std::vector<char*> cargv;
  cargv.reserve(argv.size() + 1);
  for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  struct ActionsGuard {
    posix_spawn_file_actions_t* a;
    ~ActionsGuard() { posix_spawn_file_actions_destroy(a); }
  } guard{&actions};
  if (output.kind != ProcessOutput::Kind::Inherit) {
    const std::string target = output.kind == ProcessOutput::Kind::File ? output.file.string() : "/dev/null";
    if (output.kind == ProcessOutput::Kind::File) {
      // Open here first so an unwritable log is the caller's error, not a silent child failure.
      const int fd = ::open(target.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (fd < 0)
        throw Error(target + ": cannot open the log for a helper program (" + std::strerror(errno) + ")");
      ::close(fd);
    }
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, target.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }

  ProcessStatus st;
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, cargv[0], &actions, nullptr, cargv.data(), environ);
  if (rc != 0) {
    st.error = std::string(std::strerror(rc)) + " (" + argv[0] + ")";
    return st;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      st.error = std::string("waitpid: ") + std::strerror(errno);
      return st;
    }
  }
  st.started = true;
  if (WIFEXITED(status)) {
    st.exit_code = WEXITSTATUS(status);
    // posix_spawnp reports a failed exec as exit status 127 on glibc.
    if (st.exit_code == 127) {
      st.started = false;
      st.error = "program not found or not executable (" + argv[0] + ")";
    }
  } else if (WIFSIGNALED(status)) {
    st.signal = WTERMSIG(status);
  }
  return st;
}

std::string python_interpreter() {
  if (const char* env = std::getenv("TMLAB_PYTHON"); env && *env) return env;
  return ::access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

ProcessStatus run_python(const std::filesystem::path& script, const std::vector<std::string>& args,
                         const ProcessOutput& output) {
  std::vector<std::string> argv{python_interpreter(), script.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_process(argv, output);
}

}  // namespace tmlab
