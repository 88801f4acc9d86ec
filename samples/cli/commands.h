// The subcommands of `obscura`. Each takes the arguments after its name, returns the exit code, and
// throws UsageError / ApiError (see cli_errors.h) on failure.
#ifndef OBSCURA_CLI_COMMANDS_H
#define OBSCURA_CLI_COMMANDS_H

#include "cli_args.h"

namespace obscura::cli {

int run_list_scenes(ArgumentList& arguments);
int run_list_methods(ArgumentList& arguments);
int run_list_settings(ArgumentList& arguments);
int run_render(ArgumentList& arguments);
int run_compare(ArgumentList& arguments);
int run_bench(ArgumentList& arguments);
int run_demo(ArgumentList& arguments);  // compare with the demo's scene, size and methods
int run_diff(ArgumentList& arguments);  // no GL; reports its own bad input (exit 2) on one line
int run_truth(ArgumentList& arguments);  // the geometry truth of a scene view, and its linear depth
int run_tune(ArgumentList& arguments);   // searches a method's settings against the geometry truth under a budget

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_COMMANDS_H
