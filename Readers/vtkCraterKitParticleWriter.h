/**
 * @class vtkCraterKitParticleWriter
 * @brief Writes CraterKit particles as a pkdgrav `.ss` file or a LAMMPS text dump.
 *
 * The format follows the extension (`.ss`: pkdgrav XDR, in pkdgrav units unless PkdgravUnits
 * is 0; anything else: a LAMMPS `dump custom` snapshot with id type x y z vx vy vz omegax
 * omegay omegaz radius mass and every other point array), so that a CraterKit bed can be
 * handed to pkdgrav or LAMMPS users. The input needs the point arrays Radius and Mass (or
 * Density); Velocity, AngularVelocity, Material and Id are optional.
 */
#ifndef vtkCraterKitParticleWriter_h
#define vtkCraterKitParticleWriter_h

#include "CraterKitReadersModule.h"
#include <vtkWriter.h>

class CRATERKITREADERS_EXPORT vtkCraterKitParticleWriter : public vtkWriter {
public:
  static vtkCraterKitParticleWriter* New();
  vtkTypeMacro(vtkCraterKitParticleWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  vtkSetMacro(PkdgravUnits, int);
  vtkGetMacro(PkdgravUnits, int);

protected:
  vtkCraterKitParticleWriter();
  ~vtkCraterKitParticleWriter() override;
  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;
  int PkdgravUnits = 1;

private:
  vtkCraterKitParticleWriter(const vtkCraterKitParticleWriter&) = delete;
  void operator=(const vtkCraterKitParticleWriter&) = delete;
};

#endif
