/* placeholder until the formulas helper lands; replaced before commit */
#include "cli.h"
int cli_formulas(const cli_cmd *cmd, int argc, char **argv)
{
    stc_params p;
    int done;
    stc_params_default(&p);
    int rc = cli_parse(cmd->name, "[options]", argc, argv, NULL, &p, NULL, NULL, &done);
    return rc;
}
