"""Writing the outputs: :mod:`.report` (CSV and feedback), :mod:`.summary` (the class summary),
:mod:`.gradebook` (platform gradebooks) and :mod:`.text` (quoting what a student wrote)."""
