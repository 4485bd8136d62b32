#include "hybrid/pass_distribution.h"

namespace tyndall {

namespace {
class SingleProcess : public PassDistribution {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    bool distributed() const override { return false; }
    void broadcast(std::vector<uint64_t>&) const override {}
    void gather(const std::vector<float>& mine, std::vector<float>* all) const override { *all = mine; }
    void gather(const std::vector<uint64_t>& mine, std::vector<uint64_t>* all) const override { *all = mine; }
};
}  // namespace

const PassDistribution& PassDistribution::single() {
    static const SingleProcess kSingle;
    return kSingle;
}

}  // namespace tyndall
