// A program outside abbe's tree: loads a machine file and prints the ae-arm
// deviation at one point (usage: consumer MACHINE.yaml X Y Z).
#include <cstdlib>
#include <exception>
#include <iostream>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/model_set.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: consumer MACHINE.yaml X Y Z\n";
    return 2;
  }
  try {
    const auto machine = abbe::machine::Machine::load(argv[1]);
    abbe::pipeline::ModelSet models(machine, {abbe::model::ModelKind::ae_arm});
    abbe::model::EvalPoint point;
    point.p = {std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4])};
    point.tool_length = machine.tool_length();  // as abbe predict for a CSV point
    models.evaluate(point, "consumer", 1);
    const Eigen::Vector3d e = models.deviations().at(0).e_um;
    std::cout << "consumer: |e| = " << e.norm() << " µm\n";
  } catch (const abbe::InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
