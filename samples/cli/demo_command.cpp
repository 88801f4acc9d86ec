// obscura demo: `compare` on the atrium at 640x360 with every available method (the reference
// excluded) against the geometry truth into demo-output/. Other compare options (--truth, --truth-rays,
// --json ...) pass through.
#include <string>
#include <vector>

#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"

namespace obscura::cli {

int run_demo(ArgumentList& arguments) {
    for (const char* fixed : {"--scene", "--depth", "--size", "--methods"}) {
        if (arguments.contains(fixed)) {
            throw UsageError(std::string("demo fixes the scene, size and methods (") + fixed +
                             "); run 'obscura compare' to choose them");
        }
    }
    // A depth file's options: compare would say they need --depth, which demo refuses.
    for (const char* depth_option : {"--depth-kind", "--near", "--far", "--reversed-z"}) {
        if (arguments.contains(depth_option)) {
            throw UsageError(std::string(depth_option) + " does not apply to demo (it renders the atrium; " +
                             depth_option + " reads a depth file: obscura compare --depth FILE.pfm)");
        }
    }
    std::string methods;
    for (obscura_method method : comparable_methods()) {
        methods += std::string(methods.empty() ? "" : ",") + obscura_method_name(method);
    }
    std::vector<std::string> compare = {"--scene", "atrium", "--size", "640x360", "--methods", methods};
    if (!arguments.contains("--out-dir")) compare.insert(compare.end(), {"--out-dir", "demo-output"});
    for (std::string& rest : arguments.take_rest()) compare.push_back(std::move(rest));
    ArgumentList forwarded(std::move(compare));
    return run_compare(forwarded);
}

}  // namespace obscura::cli
