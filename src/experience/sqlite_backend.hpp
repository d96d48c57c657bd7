// The SQLite engine of ExperienceStore (sqlite_backend.cpp; the background
// structural check in sqlite_backend_check.cpp). Not a public header.
#pragma once

#include <chrono>
#include <exception>
#include <memory>

#include "store_backend.hpp"

namespace earc::exp {

class SqliteBackend final : public StoreBackend {
 public:
  // Opens core.path (ExperienceStore's constructor has the contract).
  explicit SqliteBackend(StoreCore& core);
  ~SqliteBackend() override;

  void refresh(bool force) override;
  std::vector<Match> retrieve(const std::function<std::vector<Match>()>& search) override;
  SharedRows readRows(const std::vector<std::int64_t>& ids) override;
  std::optional<Experience> fetch(std::int64_t id) override;
  void awaitCheck() override;
  ExperienceStore::CheckRun checkRun() const override { return check_run_; }
  bool checkRunning() const override;
  StoredIds insert(const std::vector<Experience>& rows, double eps, SessionStamp stamp) override;
  void writeUses(const std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>>& uses) override;
  void afterWrite() override;
  bool readyToClose() override;
  void closeWritable() override;
  HistoryTail readHistory(int limit) override;
  Connection* sqliteConnection() override { return conn_.get(); }

  // The background check's state (sqlite_backend_check.cpp).
  struct BackgroundCheck;

 private:
  void open();
  // After a failed open that created the file `real`: closes the
  // connection and removes the file and its -wal, -shm and -journal
  // unless something was committed to it.
  void discardCreated(const std::string& real);
  void loadTail();
  std::int64_t meta(const char* name);
  void startCheck();
  ConnectionSettings checkSettings() const;
  // Waits for the background check (if any) to end; its error, if any, in
  // check_error_. A check starved of CPU (its idle class gets none beside
  // busy processes) is stopped and run on the calling thread instead.
  void finishCheck();
  // Stops a background check whose verdict is no longer wanted (a failed
  // open) and lets its thread go.
  void dropCheck();
  // finishCheck, then throws the check's error.
  void joinCheck();

  std::unique_ptr<Connection> conn_;
  std::unique_ptr<Statement> fetch_;
  std::unique_ptr<Statement> data_version_;
  std::int64_t loaded_data_version_ = -1;
  int writes_since_checkpoint_ = 0;
  std::chrono::steady_clock::time_point last_checkpoint_;
  // The background quick_check (StoreOptions::check_in_background): its
  // thread and what it found, shared with the thread, which a starved
  // check is left to (see finishCheck).
  std::shared_ptr<BackgroundCheck> check_;
  std::exception_ptr check_error_;     // set by the thread, read after join
  bool check_error_reported_ = false;  // thrown to a caller at least once
  bool session_pending_ = false;       // 'sessions' not yet counted
  ExperienceStore::CheckRun check_run_ = ExperienceStore::CheckRun::InOpen;
};

}  // namespace earc::exp
