// Colouring classes shared by the VS Code grammar and the Vim syntax: the
// class of a TextMate token (from its scopes) and of a Vim syntax group.
'use strict';

/** The class of a TextMate token, from its innermost meaningful scope. */
function textmateClass(scopes) {
  const rules = [
    [/^invalid\./, 'error'],
    [/^comment\./, 'comment'],
    [/^(string\.|constant\.character\.escape|punctuation\.definition\.string)/, 'string'],
    [/^keyword\.control\./, 'statement'],
    [/^storage\.type\.shape\./, 'shape'],
    [/^entity\.name\./, 'name'],
    [/^support\.type\.planner\./, 'planner'],
    [/^variable\.other\.robot\./, 'ref'],
    [/^(variable\.parameter\.|keyword\.other\.(bounds|grid-option|scatter|moving|robot-clause)\.)/, 'key'],
    [/^constant\.language\.word\./, 'word'],
    [/^constant\.language\.boolean\./, 'boolean'],
    [/^(constant\.numeric\.|keyword\.other\.unit\.)/, 'number'],
    [/^support\.variable\.metric\./, 'metric'],
    [/^support\.function\./, 'function'],
    [/^keyword\.operator\./, 'operator'],
  ];
  for (let k = scopes.length - 1; k >= 0; k--) {
    for (const [re, cls] of rules) {
      if (re.test(scopes[k])) return cls;
    }
  }
  return 'plain';
}

/** The class of a Vim syntax group (its name and the group it links to). */
function vimClass(group, linked) {
  if (linked === 'Error') return 'error';
  const map = {
    scenComment: 'comment', scenTodo: 'comment', scenBenchComment: 'comment',
    scenString: 'string', scenEscape: 'string',
    scenStatement: 'statement',
    scenShape: 'shape', scenRobotShape: 'shape', scenScatterShape: 'shape',
    scenName: 'name', scenPlanName: 'name', scenObstacleName: 'name', scenBenchName: 'name',
    scenScatterName: 'name', scenParamName: 'name',
    scenPlanner: 'planner',
    scenRobotRef: 'ref',
    scenParamKey: 'key', scenLimitKind: 'key', scenWorldKeyword: 'key', scenRobotClause: 'key',
    scenBenchKey: 'key', scenSelectKey: 'key',
    scenWord: 'word',
    scenBoolean: 'boolean',
    scenNumber: 'number', scenAngle: 'number', scenPercent: 'number',
    scenDuration: 'number', scenUnit: 'number',
    scenExprNumber: 'number', scenExprAngle: 'number', scenExprPercent: 'number',
    scenMetric: 'metric',
    scenOperator: 'operator', scenLogical: 'operator', scenEquals: 'operator',
    scenFunction: 'function', scenCalcFunction: 'function', scenChoice: 'function',
    scenCalcOperator: 'operator', scenCalcUnit: 'number', scenArrow: 'operator',
  };
  return map[group] || 'plain';
}

module.exports = { textmateClass, vimClass };
