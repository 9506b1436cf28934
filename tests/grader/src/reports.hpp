// What grading leaves behind, per submission: the feedback a student reads (the same text
// `./lab test --student` prints), results.json in Gradescope's format and a JUnit report per task;
// and for the class, gradebook.csv. Text that a submission could influence (its output, its
// compiler messages) is made printable first: no terminal escapes, valid UTF-8, bounded.
#pragma once

#include "grading.hpp"
#include "words.hpp"

#include <string>
#include <vector>

namespace springlab::grader {

/// Task `task`'s part of the feedback: a heading, one line per test (a hidden test's marked),
/// the first failure of each failing test explained, and a closing count.
std::string task_feedback(const SubmissionResult& result, int task, const Kit& kit);

/// The closing summary: one line per task graded and the total.
std::string summary_feedback(const SubmissionResult& result);

/// Every task's feedback, then the summary (feedback.txt).
std::string feedback(const SubmissionResult& result, const Kit& kit);

/// What students may see before the due date: `result` without its hidden tests (their points
/// out of the totals too).
SubmissionResult visible_part(const SubmissionResult& result);

/// results.json for Gradescope: one entry per test with score, max_score, status, output, tags
/// (taskN and the test's own) and visibility ("visible", or "after_due_date" for a hidden test);
/// the run's output summarises the visible tests only, its score counts every test; `seconds` is
/// the run's execution_time.
std::string results_json(const SubmissionResult& result, double seconds);

/// A JUnit XML report of one task.
std::string junit_report(const SubmissionResult& result, int task);

/// `field` as one CSV field: quoted when it holds a comma, a quote or a line break, and with a
/// leading ' when a spreadsheet would read it as a formula (=, +, -, @).
std::string csv(std::string field);

/// gradebook.csv: "submission,task1,task2,task3,task4,task5,total" and one row per submission.
std::string gradebook(const std::vector<SubmissionResult>& results);

/// review.csv: "submission,task,calls" and a row per task whose code calls what no task needs,
/// then, when `grader_note` is not empty, a row "(every submission),," with it (how the run
/// confined submission code, when that is weaker than it should be); "" when there is nothing.
std::string review_list(const std::vector<SubmissionResult>& results,
                        const std::string& grader_note = "");

/// A submission's folder in --out: its name, unless that is one of the grader's own files there
/// (or hidden), which would clash: then "submission-" and the name.
std::string results_folder(const std::string& name);

/// Writes `text` to `file` whole or not at all: into a file beside it, checked as it is written
/// and closed, then renamed over `file`. Throws std::runtime_error naming the file and why
/// ("No space left on device").
void write_file(const fs::path& file, const std::string& text);

}  // namespace springlab::grader
