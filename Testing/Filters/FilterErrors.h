// Runs a filter (on an input) and collects the error messages it reports.
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

/// Updates `algorithm`, collecting its error messages.
inline std::vector<std::string> updateCollectingErrors(vtkAlgorithm* algorithm)
{
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call)); });
  algorithm->AddObserver(vtkCommand::ErrorEvent, onError);
  algorithm->Update();
  algorithm->RemoveObservers(vtkCommand::ErrorEvent);
  return errors;
}

/// Runs `filter` on `input`, collecting its error messages.
inline std::vector<std::string> runCollectingErrors(vtkAlgorithm* filter, vtkDataObject* input)
{
  filter->SetInputDataObject(0, input);
  return updateCollectingErrors(filter);
}

} // namespace igatest
