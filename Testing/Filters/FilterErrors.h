// Runs a filter on an input and collects the error messages it reports.
#pragma once

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"

#include <string>
#include <vector>

namespace igatest
{

/// Runs `filter` on `input`, collecting its error messages.
inline std::vector<std::string> runCollectingErrors(vtkAlgorithm* filter, vtkDataObject* input)
{
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call)); });
  filter->AddObserver(vtkCommand::ErrorEvent, onError);
  filter->SetInputDataObject(0, input);
  filter->Update();
  filter->RemoveObservers(vtkCommand::ErrorEvent);
  return errors;
}

} // namespace igatest
